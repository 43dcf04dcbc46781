#include "configuration_flags.hpp"

#include <string>
#include <type_traits>
#include <variant>

#include "rgbdvo/odometry/odometry_parameters.hpp"
#include "rgbdvo/pipeline/run_parameters.hpp"

namespace rgbdvo::cli {
namespace {
const char* kOdometryGroup =
    "Odometry (see docs/method.md; --preset paper = Fiala & Ufkes 2011 exactly)";
const char* kRunGroup = "Threads and memory (same results whatever their values)";

// What --help shows for a parameter's value.
template <typename Options>
std::string TypeName(const Parameter<Options>& p) {
  Options scratch;
  return std::visit(
      [](auto* field) -> std::string {
        using T = std::remove_pointer_t<decltype(field)>;
        if constexpr (std::is_enum_v<T>) return "NAME";
        if constexpr (std::is_same_v<T, double>) return "FLOAT";
        return "INT";
      },
      p.field(scratch));
}

// A flag for each parameter (a boolean's two), described with its default in `defaults`.
template <typename Options>
void AddFlags(CLI::App* cmd, const std::vector<Parameter<Options>>& parameters,
              const Options& defaults, const char* group,
              std::vector<std::unique_ptr<ConfigurationFlags::Given>>* given) {
  for (const Parameter<Options>& p : parameters) {
    auto g = std::make_unique<ConfigurationFlags::Given>();
    const std::string name = std::string("--") + p.flag;
    const std::string help = std::string(p.help) + " [" + p.key + "]";
    if (p.IsBool()) {
      const bool on_by_default = p.Get(defaults) == "true";
      g->on = cmd->add_flag(name)
                  ->description(help + (on_by_default ? " (default)" : ""))
                  ->group(group);
      g->off = cmd->add_flag("--no-" + std::string(p.flag))
                   ->description("not " + name + (on_by_default ? "" : " (default)"))
                   ->group(group);
    } else {
      g->on =
          cmd->add_option(name, g->text, help)
              ->group(group)
              ->type_name(p.IsNumber() ? TypeName(p) + " in " + FormatRange(p.range) : TypeName(p))
              ->default_str(p.Get(defaults))
              ->check([&p](const std::string& value) {
                Options scratch;
                try {
                  p.Set(value, &scratch);
                } catch (const std::invalid_argument& e) {
                  return std::string(e.what());
                }
                return std::string();
              });
    }
    given->push_back(std::move(g));
  }
}

// The flags given (given[i] for parameters[i]) applied to `options`.
template <typename Options>
void ApplyGiven(const std::vector<Parameter<Options>>& parameters,
                const std::unique_ptr<ConfigurationFlags::Given>* given, Options* options) {
  for (size_t i = 0; i < parameters.size(); ++i) {
    const ConfigurationFlags::Given& g = *given[i];
    if (g.off && g.off->count() > 0 && g.on->count() > 0)
      throw CLI::ExcludesError(g.on->get_name(), g.off->get_name());
    if (g.off && g.off->count() > 0) parameters[i].Set("false", options);
    if (g.on->count() > 0) parameters[i].Set(g.off ? "true" : g.text, options);
  }
}

}  // namespace

ConfigurationFlags::ConfigurationFlags(CLI::App* cmd, const RunOptions& run_defaults)
    : run_defaults_(run_defaults) {
  cmd->add_option("--preset", preset_, "default (most accurate) or paper (Fiala & Ufkes 2011)")
      ->group(kOdometryGroup)
      ->check(CLI::IsMember({"default", "paper"}))
      ->capture_default_str();
  cmd->add_option("--config", config_,
                  "configuration file, 'key = value' lines as --dump-config writes them; applied "
                  "after --preset, before the flags")
      ->group(kOdometryGroup);
  cmd->add_flag("--dump-config", dump_,
                "print the configuration (--preset, --config and the flags applied) as a "
                "configuration file, and exit")
      ->group(kOdometryGroup);
  AddFlags(cmd, OdometryParameters(), OdometryOptions{}, kOdometryGroup, &given_);
  AddFlags(cmd, RunParameters(), run_defaults_, kRunGroup, &given_);
}

Configuration ConfigurationFlags::Resolve() const {
  Configuration c{PresetOptions(preset_), run_defaults_};
  if (!config_.empty()) ApplyConfigFile(config_, &c.odometry, &c.run);
  ApplyGiven(OdometryParameters(), given_.data(), &c.odometry);
  ApplyGiven(RunParameters(), given_.data() + OdometryParameters().size(), &c.run);
  c.odometry.Check();
  c.run.Check();
  return c;
}

std::string ConfigurationFlags::DumpConfig() const {
  std::string header = "# rgbdvo " RGBDVO_VERSION " configuration: --preset " + preset_;
  if (!config_.empty()) header += ", --config " + config_;
  const Configuration c = Resolve();
  return header + ", then the flags given\n" + ConfigurationText(c.odometry, c.run);
}

}  // namespace rgbdvo::cli
