#include "odometry_flags.hpp"

#include <string>
#include <type_traits>
#include <variant>

#include "rgbdvo/odometry/odometry_parameters.hpp"

namespace rgbdvo::cli {
namespace {
const char* kGroup = "Odometry (see docs/method.md; --preset paper = Fiala & Ufkes 2011 exactly)";

// What --help shows for a parameter's value.
std::string TypeName(const OdometryParameter& p) {
  OdometryOptions scratch;
  return std::visit(
      [](auto* field) -> std::string {
        using T = std::remove_pointer_t<decltype(field)>;
        if constexpr (std::is_enum_v<T>) return "NAME";
        if constexpr (std::is_same_v<T, double>) return "FLOAT";
        return "INT";
      },
      p.field(scratch));
}

}  // namespace

OdometryFlags::OdometryFlags(CLI::App* cmd) {
  cmd->add_option("--preset", preset_, "default (most accurate) or paper (Fiala & Ufkes 2011)")
      ->group(kGroup)
      ->check(CLI::IsMember({"default", "paper"}))
      ->capture_default_str();
  cmd->add_option("--config", config_,
                  "configuration file, 'key = value' lines as --dump-config writes them; applied "
                  "after --preset, before the flags")
      ->group(kGroup);
  cmd->add_flag("--dump-config", dump_,
                "print the configuration (--preset, --config and the flags applied) as a "
                "configuration file, and exit")
      ->group(kGroup);
  const OdometryOptions defaults;
  for (const OdometryParameter& p : OdometryParameters()) {
    auto given = std::make_unique<Given>();
    const std::string name = std::string("--") + p.flag;
    const std::string help = std::string(p.help) + " [" + p.key + "]";
    if (p.IsBool()) {
      const bool on_by_default = p.Get(defaults) == "true";
      given->on = cmd->add_flag(name)
                      ->description(help + (on_by_default ? " (default)" : ""))
                      ->group(kGroup);
      given->off = cmd->add_flag("--no-" + std::string(p.flag))
                       ->description("not " + name + (on_by_default ? "" : " (default)"))
                       ->group(kGroup);
    } else {
      given->on = cmd->add_option(name, given->text, help)
                      ->group(kGroup)
                      ->type_name(TypeName(p))
                      ->default_str(p.Get(defaults))
                      ->check([&p](const std::string& value) {
                        OdometryOptions scratch;
                        try {
                          p.Set(value, &scratch);
                        } catch (const std::invalid_argument& e) {
                          return std::string(e.what());
                        }
                        return std::string();
                      });
    }
    given_.push_back(std::move(given));
  }
}

OdometryOptions OdometryFlags::Resolve() const {
  OdometryOptions o = PresetOptions(preset_);
  if (!config_.empty()) ApplyConfigFile(config_, &o);
  const std::vector<OdometryParameter>& parameters = OdometryParameters();
  for (size_t i = 0; i < parameters.size(); ++i) {
    const Given& g = *given_[i];
    if (g.off && g.off->count() > 0 && g.on->count() > 0)
      throw CLI::ExcludesError(g.on->get_name(), g.off->get_name());
    if (g.off && g.off->count() > 0) parameters[i].Set("false", &o);
    if (g.on->count() > 0) parameters[i].Set(g.off ? "true" : g.text, &o);
  }
  o.Check();
  return o;
}

std::string OdometryFlags::DumpConfig() const {
  std::string header = "# rgbdvo " RGBDVO_VERSION " odometry configuration: --preset " + preset_;
  if (!config_.empty()) header += ", --config " + config_;
  return header + ", then the flags given\n" + Resolve().ToString();
}

}  // namespace rgbdvo::cli
