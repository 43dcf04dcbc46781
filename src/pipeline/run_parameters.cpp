#include "rgbdvo/pipeline/run_parameters.hpp"

#include <functional>
#include <istream>

namespace rgbdvo {
namespace {

using R = RunOptions;

const std::string kThreadsHelp =
    "1 = everything on one core (OpenCV's loops too); N >= 2 = N feature workers (decode, and "
    "SIFT with --no-track) while the main thread matches, estimates and writes in frame order "
    "(same results); 0 = automatic: the hardware concurrency, at most " +
    std::to_string(RunOptions::kMaxAutoThreads);

const std::vector<RunParameter> kParameters = {
    {"run.threads",
     "threads",
     kThreadsHelp.c_str(),
     [](R& r) -> ParameterRef { return &r.threads; },
     {0, 256}},
    {"run.queue_frames",
     "queue-frames",
     "frames read ahead of the odometry at most, raised to the number of workers (bounds memory)",
     [](R& r) -> ParameterRef { return &r.queue_frames; },
     {1, 256}},
    {"run.parallel_keyframe_sift", "parallel-keyframe-sift",
     "with --threads 2 or more and tracking: run a new keyframe's SIFT and the frame before's "
     "side by side (shorter keyframe frames; more CPU where the two cores slow each other; same "
     "results)",
     [](R& r) -> ParameterRef { return &r.parallel_keyframe_sift; }},
};

}  // namespace

const std::vector<RunParameter>& RunParameters() { return kParameters; }

const RunParameter* FindRunParameter(const std::string& key) {
  for (const RunParameter& p : kParameters)
    if (key == p.key) return &p;
  return nullptr;
}

std::string ConfigurationText(const OdometryOptions& odometry, const RunOptions& run) {
  std::string s = odometry.ToString();
  for (const RunParameter& p : kParameters) s += std::string(p.key) + " = " + p.Get(run) + "\n";
  return s;
}

namespace {
// ApplyConfig's `other`: the run's keys into `run`.
std::function<bool(const std::string&, const std::string&)> RunKeys(RunOptions* run) {
  return [run](const std::string& key, const std::string& value) {
    const RunParameter* p = FindRunParameter(key);
    if (p) p->Set(value, run);
    return p != nullptr;
  };
}
}  // namespace

void ApplyConfig(std::istream& in, const std::string& name, OdometryOptions* odometry,
                 RunOptions* run) {
  ApplyConfig(in, name, odometry, RunKeys(run));
}

void ApplyConfigFile(const std::string& path, OdometryOptions* odometry, RunOptions* run) {
  ApplyConfigFile(path, odometry, RunKeys(run));
}

}  // namespace rgbdvo
