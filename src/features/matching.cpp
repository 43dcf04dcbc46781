#include "rgbdvo/features/matching.hpp"

#include <opencv2/features2d.hpp>
#include <stdexcept>

namespace rgbdvo {

void MatchOptions::Check() const {
  if (!(ratio > 0 && ratio <= 1))
    throw std::invalid_argument("MatchOptions.ratio must be in (0, 1]");
}

std::vector<cv::DMatch> MatchFeatures(const MatchOptions& o, const Features& prev,
                                      const Features& cur) {
  std::vector<cv::DMatch> out;
  if (prev.size() < 2 || cur.size() < 2) return out;
  // As floats, with the same (exact) distances: cv::BFMatcher's L2 on bytes made a whole
  // --preset paper run twice as slow.
  cv::Mat prev_desc, cur_desc;
  prev.descriptors.convertTo(prev_desc, CV_32F);
  cur.descriptors.convertTo(cur_desc, CV_32F);
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> forward;  // prev -> cur, two nearest
  matcher.knnMatch(prev_desc, cur_desc, forward, 2);
  // Ratio test first; the mutual check then needs the backward nearest neighbour only for the
  // cur features that survived it (same distances as a full backward pass, so same result).
  std::vector<cv::DMatch> candidates;
  for (const std::vector<cv::DMatch>& knn : forward) {
    if (knn.size() < 2) continue;
    if (!(knn[0].distance < o.ratio * knn[1].distance)) continue;
    candidates.push_back(knn[0]);
  }
  if (!o.mutual) return candidates;
  std::vector<int> row_of_cur(cur.size(), -1), cur_of_row;
  for (const cv::DMatch& m : candidates)
    if (row_of_cur[m.trainIdx] < 0) {
      row_of_cur[m.trainIdx] = static_cast<int>(cur_of_row.size());
      cur_of_row.push_back(m.trainIdx);
    }
  cv::Mat queries(static_cast<int>(cur_of_row.size()), cur_desc.cols, cur_desc.type());
  for (size_t r = 0; r < cur_of_row.size(); ++r)
    cur_desc.row(cur_of_row[r]).copyTo(queries.row(static_cast<int>(r)));
  std::vector<cv::DMatch> backward;  // candidate cur -> prev, nearest
  if (!cur_of_row.empty()) matcher.match(queries, prev_desc, backward);
  std::vector<int> best_prev_for_row(cur_of_row.size(), -1);
  for (const cv::DMatch& m : backward) best_prev_for_row[m.queryIdx] = m.trainIdx;
  for (const cv::DMatch& m : candidates)
    if (best_prev_for_row[row_of_cur[m.trainIdx]] == m.queryIdx) out.push_back(m);
  return out;
}

}  // namespace rgbdvo
