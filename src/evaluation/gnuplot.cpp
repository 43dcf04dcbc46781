#include "rgbdvo/evaluation/gnuplot.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/util/temp_dir.hpp"

namespace rgbdvo {
namespace {

namespace fs = std::filesystem;

// Runs `program script` in `dir` with stderr into `err_path` and no shell in between: the
// program's name and the paths reach exec() as they are. Returns the exit code, 127 when the
// program cannot be started, -1 when it did not exit normally.
int RunInFolder(const std::string& program, const fs::path& dir, const std::string& script,
                const fs::path& err_path) {
  // Everything the child needs is prepared before fork(): after it only async-signal-safe calls.
  const std::string dir_s = dir.string(), err_s = err_path.string();
  std::vector<char*> argv = {const_cast<char*>(program.c_str()), const_cast<char*>(script.c_str()),
                             nullptr};
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("plot: cannot start " + program);
  if (pid == 0) {
    const int err = open(err_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int in = open("/dev/null", O_RDONLY);
    if (err < 0 || in < 0 || dup2(err, 2) < 0 || dup2(in, 0) < 0 || chdir(dir_s.c_str()) != 0)
      _exit(126);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string GnuplotQuoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\'')
      out += "''";
    else
      out += (byte < 0x20 || byte == 0x7f) ? ' ' : c;
  }
  return out + "'";
}

void RenderGnuplot(const std::string& gnuplot, const std::string& script,
                   const std::vector<std::pair<std::string, std::string>>& files,
                   const std::string& png_path) {
  const ScopedTempDir scoped_tmp("rgbdvo_plot_");
  const fs::path tmp = scoped_tmp.path();
  for (const auto& [name, content] : files) {
    std::ofstream out(tmp / name);
    out << content;
    if (!out) throw std::runtime_error((tmp / name).string() + ": cannot write plot data");
  }
  {
    std::ofstream out(tmp / "plot.gp");
    out << script;
    if (!out) throw std::runtime_error((tmp / "plot.gp").string() + ": cannot write");
  }
  const int code = RunInFolder(gnuplot, tmp, "plot.gp", tmp / "err.txt");
  if (code == 127)
    throw std::runtime_error("plot: '" + gnuplot +
                             "' not found; install the Debian package gnuplot-nox "
                             "(scripts/setup.sh does)");
  if (code != 0) {
    std::string err = ReadAll(tmp / "err.txt");
    std::replace(err.begin(), err.end(), '\n', ' ');
    throw std::runtime_error("plot: " + gnuplot + " failed (exit " + std::to_string(code) +
                             ") writing " + png_path + ": " + err.substr(0, 300));
  }
  std::error_code ec;
  const fs::path image = tmp / "plot.png";
  if (!fs::exists(image, ec) || fs::file_size(image, ec) == 0)
    throw std::runtime_error("plot: " + png_path + ": gnuplot wrote no image");
  const fs::path parent = fs::path(png_path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);  // a failure shows in the copy
  fs::copy_file(image, png_path, fs::copy_options::overwrite_existing, ec);
  if (ec) throw std::runtime_error("plot: " + png_path + ": " + ec.message());
}

}  // namespace rgbdvo
