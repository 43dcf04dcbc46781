#include "rgbdvo/evaluation/evaluation_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace rgbdvo {
namespace {

std::string JsonString(const std::string& s) {
  std::ostringstream out;
  out << '"';
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << static_cast<int>(c)
          << std::dec << std::setfill(' ');
    } else {
      out << c;
    }
  }
  return out.str() + '"';
}

// A number, or null when it was not computed or is not finite (JSON has no inf or nan; the
// reason is given beside it).
std::string JsonNumber(double v, bool computed) {
  if (!computed || !std::isfinite(v)) return "null";
  std::ostringstream out;
  out << std::setprecision(9) << v;
  return out.str();
}

// The statistics, or null for each when they could not be computed (no pose or pair): a reader
// must not mistake "not computed" for a perfect 0.
std::string JsonStats(const ErrorStats& s, bool computed) {
  return "{\"rmse\": " + JsonNumber(s.rmse, computed) +
         ", \"mean\": " + JsonNumber(s.mean, computed) +
         ", \"median\": " + JsonNumber(s.median, computed) +
         ", \"max\": " + JsonNumber(s.max, computed) + "}";
}

// "1s", "5f", "0.5m": the step in the table's row names.
std::string DeltaShort(const EvaluationOptions& o) {
  std::ostringstream d;
  d << o.delta
    << (o.delta_unit == DeltaUnit::kSeconds  ? "s"
        : o.delta_unit == DeltaUnit::kFrames ? "f"
                                             : "m");
  return d.str();
}

// What the alignment did, for the table: "rigid alignment without scale" (the TUM wording).
std::string AlignmentLong(const EvaluationOptions& o, const AteResult& ate) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(6);
  switch (o.align) {
    case Alignment::kSe3:
      s << "rigid alignment without scale";
      break;
    case Alignment::kSim3:
      s << "rigid alignment with scale";
      break;
    case Alignment::kScale:
      s << "scale correction only";
      break;
    case Alignment::kOrigin:
      s << "first poses aligned";
      break;
    case Alignment::kNone:
      s << "no alignment";
      break;
  }
  const bool fitted =
      o.align == Alignment::kSe3 || o.align == Alignment::kSim3 || o.align == Alignment::kScale;
  if (fitted && o.align_first > 0) s << " fitted to the first " << ate.aligned_on << " of them";
  if (ate.success && (o.align == Alignment::kSim3 || o.align == Alignment::kScale))
    s << " (scale " << ate.scale << ")";
  return s.str();
}

}  // namespace

EvaluationReport EvaluateFiles(const std::string& gt_path, const std::string& est_path,
                               const EvaluationOptions& options) {
  options.Check();
  const Trajectory gt = ReadTrajectory(gt_path);
  const Trajectory est = ReadTrajectory(est_path);
  EvaluationReport report;
  report.groundtruth_path = gt_path;
  report.estimate_path = est_path;
  report.groundtruth_poses = static_cast<int>(gt.poses.size());
  report.estimate_poses = static_cast<int>(est.poses.size());
  report.groundtruth_repeated = gt.repeated_timestamps;
  report.estimate_repeated = est.repeated_timestamps;
  report.options = options;
  report.ate = ComputeAte(gt.poses, est.poses, options);
  if (report.ate.matched == 0) {
    std::ostringstream msg;
    msg << std::fixed << std::setprecision(3) << est_path << ": no pose within " << options.max_dt_s
        << " s of a ground truth pose in " << gt_path << " (estimate spans "
        << est.poses.front().timestamp + options.t_offset_s << ".."
        << est.poses.back().timestamp + options.t_offset_s << " s";
    if (options.t_offset_s != 0) msg << " after --t-offset";
    msg << ", ground truth " << gt.poses.front().timestamp << ".." << gt.poses.back().timestamp
        << " s): no overlapping timestamps";
    throw std::runtime_error(msg.str());
  }
  report.rpe = ComputeRpe(gt.poses, est.poses, options, report.ate.scale);
  return report;
}

std::string EvaluationReport::Table() const {
  std::ostringstream s;
  s << "ground truth: " << groundtruth_path << " (" << groundtruth_poses << " poses)\n"
    << "estimate:     " << estimate_path << " (" << estimate_poses << " poses)\n";
  if (options.t_offset_s != 0)
    s << "time offset:  " << std::showpos << options.t_offset_s << std::noshowpos
      << " s added to the estimate's timestamps\n";
  s << "ATE: " << ate.matched << " poses matched within " << options.max_dt_s << " s, "
    << AlignmentLong(options, ate) << "\n"
    << "RPE: " << rpe.pairs << " pairs " << DescribeDelta(options) << "\n";
  if (groundtruth_repeated + estimate_repeated > 0)
    s << "note: rows with a repeated timestamp (the last one kept, as the TUM tools do): "
      << estimate_repeated << " in the estimate, " << groundtruth_repeated
      << " in the ground truth\n";
  s << "\n";
  s << std::left << std::setw(22) << "" << std::right << std::setw(10) << "rmse" << std::setw(10)
    << "mean" << std::setw(10) << "median" << std::setw(10) << "max"
    << "\n";
  auto row = [&](const std::string& name, bool ok, const ErrorStats& e, int precision,
                 const std::string& why) {
    s << std::left << std::setw(22) << name << std::right;
    if (!ok) {
      s << "  n/a (" << why << ")\n";
      return;
    }
    s << std::fixed << std::setprecision(precision) << std::setw(10) << e.rmse << std::setw(10)
      << e.mean << std::setw(10) << e.median << std::setw(10) << e.max << "\n";
  };
  const std::string d = DeltaShort(options);
  row("ATE (m)", ate.success, ate.error_m, 4, ate.reason);
  row("RPE trans (m/" + d + ")", rpe.success, rpe.trans_m, 4, rpe.reason);
  row("RPE rot (deg/" + d + ")", rpe.success, rpe.rot_deg, 3, rpe.reason);
  return s.str();
}

std::string EvaluationReport::Json() const {
  const bool scaled = options.align == Alignment::kSim3 || options.align == Alignment::kScale;
  std::ostringstream s;
  s << std::setprecision(9) << "{\"groundtruth\": " << JsonString(groundtruth_path)
    << ", \"estimate\": " << JsonString(estimate_path)
    << ", \"groundtruth_poses\": " << groundtruth_poses
    << ", \"estimate_poses\": " << estimate_poses
    << ", \"groundtruth_repeated\": " << groundtruth_repeated
    << ", \"estimate_repeated\": " << estimate_repeated
    << ", \"max_dt_s\": " << JsonNumber(options.max_dt_s, true)
    << ", \"t_offset_s\": " << JsonNumber(options.t_offset_s, true)
    << ", \"delta_s\": " << JsonNumber(options.delta, options.delta_unit == DeltaUnit::kSeconds)
    << ", \"delta\": " << JsonNumber(options.delta, true)
    << ", \"delta_unit\": " << JsonString(DeltaUnitName(options.delta_unit))
    << ", \"align\": " << JsonString(AlignmentName(options.align))
    << ", \"align_first\": " << options.align_first
    << ",\n \"ate\": {\"success\": " << (ate.success ? "true" : "false")
    << ", \"matched\": " << ate.matched << ", \"aligned_on\": " << ate.aligned_on
    << ", \"scale\": " << JsonNumber(ate.scale, ate.success && scaled)
    << ", \"reason\": " << JsonString(ate.reason)
    << ", \"error_m\": " << JsonStats(ate.error_m, ate.success)
    << "},\n \"rpe\": {\"success\": " << (rpe.success ? "true" : "false")
    << ", \"pairs\": " << rpe.pairs << ", \"reason\": " << JsonString(rpe.reason)
    << ", \"trans_m\": " << JsonStats(rpe.trans_m, rpe.success)
    << ", \"rot_deg\": " << JsonStats(rpe.rot_deg, rpe.success) << "}}\n";
  return s.str();
}

std::string ComparisonTable(const std::vector<EvaluationReport>& reports) {
  if (reports.empty()) return "";
  const EvaluationReport& first = reports.front();
  const EvaluationOptions& o = first.options;
  const bool scaled = o.align == Alignment::kSim3 || o.align == Alignment::kScale;
  std::ostringstream s;
  s << "ground truth: " << first.groundtruth_path << " (" << first.groundtruth_poses << " poses)\n";
  if (o.t_offset_s != 0)
    s << "time offset:  " << std::showpos << o.t_offset_s << std::noshowpos
      << " s added to the estimates' timestamps\n";
  s << "ATE: poses matched within " << o.max_dt_s << " s, alignment " << AlignmentName(o.align);
  if (o.align_first > 0) s << " fitted to the first " << o.align_first << " matched poses";
  s << "\nRPE: pairs " << DescribeDelta(o) << "\n"
    << "ATE rmse, mean, median, max of the position errors in m; RPE rmse per step\n\n";
  size_t name_w = 8;
  for (const EvaluationReport& r : reports) name_w = std::max(name_w, r.estimate_path.size());
  const std::string d = DeltaShort(o);
  s << std::left << std::setw(name_w + 2) << "estimate" << std::right << std::setw(7) << "poses"
    << std::setw(9) << "matched";
  if (scaled) s << std::setw(10) << "scale";
  s << std::setw(11) << "ATE rmse" << std::setw(10) << "mean" << std::setw(10) << "median"
    << std::setw(10) << "max" << std::setw(8) << "pairs" << std::setw(14) << "RPE m/" + d
    << std::setw(14) << "RPE deg/" + d << "\n";
  for (const EvaluationReport& r : reports) {
    s << std::left << std::setw(name_w + 2) << r.estimate_path << std::right << std::setw(7)
      << r.estimate_poses << std::setw(9) << r.ate.matched << std::fixed;
    if (scaled) {
      if (r.ate.success)
        s << std::setprecision(4) << std::setw(10) << r.ate.scale;
      else
        s << std::setw(10) << "n/a";
    }
    if (r.ate.success)
      s << std::setprecision(4) << std::setw(11) << r.ate.error_m.rmse << std::setw(10)
        << r.ate.error_m.mean << std::setw(10) << r.ate.error_m.median << std::setw(10)
        << r.ate.error_m.max;
    else
      s << std::setw(11) << "n/a" << std::setw(30) << "";
    s << std::setw(8) << r.rpe.pairs;
    if (r.rpe.success)
      s << std::setprecision(4) << std::setw(14) << r.rpe.trans_m.rmse << std::setprecision(3)
        << std::setw(14) << r.rpe.rot_deg.rmse;
    else
      s << std::setw(14) << "n/a" << std::setw(14) << "n/a";
    s << "\n";
  }
  for (const EvaluationReport& r : reports) {
    if (!r.ate.success) s << r.estimate_path << ": " << r.ate.Brief() << "\n";
    if (!r.rpe.success) s << r.estimate_path << ": " << r.rpe.Brief() << "\n";
    if (r.estimate_repeated > 0)
      s << r.estimate_path << ": " << r.estimate_repeated
        << " rows with a repeated timestamp (the last one kept)\n";
  }
  return s.str();
}

std::string ComparisonJson(const std::vector<EvaluationReport>& reports) {
  std::string out = "[";
  for (size_t k = 0; k < reports.size(); ++k) {
    std::string obj = reports[k].Json();
    obj.pop_back();  // the newline
    out += (k ? ",\n " : "") + obj;
  }
  return out + "]\n";
}

}  // namespace rgbdvo
