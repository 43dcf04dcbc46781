#pragma once
// Drawing a figure with gnuplot (pngcairo terminal): a generated script and its data files in a
// temporary folder, gnuplot started there without a shell, the image copied to where it was
// asked for. Shared by the trajectory plot and the evaluation plots.

#include <string>
#include <utility>
#include <vector>

namespace rgbdvo {

// A gnuplot single-quoted string: gnuplot expands nothing inside single quotes (no backquote
// command substitution, no @macros, no backslash escapes), a quote is written twice, and control
// characters (newlines end a command) become spaces. Our strings (paths, titles, reasons) thus
// stay text, whatever a user or a recording's name puts in them.
std::string GnuplotQuoted(const std::string& s);

// Writes `files` (name, content) and `script` into a new temporary folder, runs `gnuplot` on the
// script there (the script must write 'plot.png' in its folder) and copies the image to
// png_path, creating its folder. The user's path never enters the script. Throws when gnuplot
// is missing or fails (naming the command and its message) or writes no image; the temporary
// folder is removed in every case.
void RenderGnuplot(const std::string& gnuplot, const std::string& script,
                   const std::vector<std::pair<std::string, std::string>>& files,
                   const std::string& png_path);

}  // namespace rgbdvo
