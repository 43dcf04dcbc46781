#pragma once
// Calibration files by name: `--calib tum_fr1` finds tum_fr1.yaml in the installed calibrations
// (share/rgbdvo/calib beside the program, or the install prefix this library was built for) or
// in the source tree's calib/; a path names a file directly.

#include <string>
#include <vector>

namespace rgbdvo {

struct CalibrationEntry {
  std::string name;         // file name without .yaml: what --calib accepts
  std::string path;         // where it was found
  std::string description;  // the file's description (empty if it has none or cannot be read)
};

// The folders searched for a named calibration, first match wins: each folder of the
// environment variable RGBDVO_CALIB_PATH (colon-separated), share/rgbdvo/calib next to the
// running program's bin/, the install prefix's, and the source tree's calib/. Only folders that
// exist are listed.
std::vector<std::string> CalibrationSearchPath();

// The file `name_or_path` refers to: itself if it is an existing file; else, for a bare name
// (no '/'), NAME or NAME.yaml in the first folder of CalibrationSearchPath() that has it.
// Throws std::runtime_error naming what was asked and where it looked.
std::string FindCalibration(const std::string& name_or_path);

// Every *.yaml of the search path, by name (a name found twice: the first folder's), sorted.
std::vector<CalibrationEntry> ListCalibrations();

}  // namespace rgbdvo
