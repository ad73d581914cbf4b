// The option builders the commands share (Cli.cpp, SweepCli.cpp): options named and bounded
// as the scene-file keys they override (scene/SettingNames.h, scene/SettingLimits.h), and the
// option sets several commands take.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "master/commands/RenderOptions.h"
#include "scene/SettingLimits.h"
#include "scene/SettingNames.h"

namespace prism {

// An option whose value is one of a setting's names (scene/SettingNames.h), spelt as in scene
// files or with '-' for '_', in any case; help and errors list the canonical names.
template <typename T, typename E>
CLI::Option* addNamed(CLI::App* command, const std::string& flags, T& target,
                      const NameTable<E>& names, const std::string& help) {
  CLI::Validator toValue(
      [names](std::string& text) {
        const std::optional<E> value = names.find(text);
        if (!value) return "unknown value '" + text + "' (expected " + names.list() + ")";
        text = std::to_string(static_cast<int>(*value));  // CLI11 converts enums from integers
        return std::string();
      },
      "");
  return command->add_option(flags, target, help)
      ->transform(toValue)
      ->option_text(names.list("|", "|"));
}

// An option bounded like the scene-file key it overrides (scene/SettingLimits.h).
template <typename T>
CLI::Option* addLimited(CLI::App* command, const std::string& flags, T& target,
                        const SettingLimit& limit, const std::string& help) {
  return command->add_option(flags, target, help)->check(CLI::Range(limit.min, limit.max));
}

// -W, -H and -s: every command that renders has them.
void addImageSizeOptions(CLI::App* command, RenderOptions& o, const std::string& sppHelp);
// --memory-limit (docs/reliability.md).
void addMemoryLimitOption(CLI::App* command, RenderOptions& o);
// The scene file: every command's one positional argument.
void addSceneArgument(CLI::App* command, RenderOptions& o);

// The heading the caustics options are listed under in --help.
inline constexpr const char* kCausticsGroup = "Caustics (override the scene's 'caustics' section)";
// The caustics options `render`, `view`, `speedup` and `sweep` share: the method, the photon
// budget and the caustic-map parameters.
void addCausticMethodOptions(CLI::App* command, RenderOptions& o);

}  // namespace prism
