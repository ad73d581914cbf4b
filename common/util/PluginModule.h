// Prism's own shared modules, loaded with dlopen() the first time a process needs them, so that
// no process pays at start-up for a large library it may never use (docs/dependencies.md):
// OpenImageIO (image/OiioModule.h), Qt (gui/ViewerModule.h) and MPI (transport/MpiModule.h).
#pragma once

#include <functional>
#include <string>

namespace prism {

struct PluginModuleSearch {
  std::string fileName;             // e.g. "prism_viewer.so"; looked for next to the executable
  std::string environmentVariable;  // when set, its value is the only place looked at
  std::string buildPath;            // where the build put it (may be empty)
  std::string entryName;            // the extern "C" function the module exports
  bool global = false;  // RTLD_GLOBAL: the module's libraries load plug-ins of their own
};

// Loads the first candidate that opens, exports entryName and satisfies accept(entry), and
// returns the entry (the module stays loaded until exit). Returns nullptr and fills *tried with
// one line per candidate and why it was passed over when none does.
void* loadPluginModule(const PluginModuleSearch& search,
                       const std::function<bool(void* entry)>& accept, std::string* tried);

// Loads the module and returns the table of functions its entry returns (an Api with an int
// `version` first), or nullptr, with *tried filled, when no candidate has this build's version.
template <typename Api>
const Api* loadPluginApi(const PluginModuleSearch& search, int version, std::string* tried) {
  const Api* api = nullptr;
  loadPluginModule(
      search,
      [&api, version](void* entry) {
        const Api* candidate = reinterpret_cast<const Api* (*)()>(entry)();
        if (!candidate || candidate->version != version) return false;
        api = candidate;
        return true;
      },
      tried);
  return api;
}

// The error text for a module that was not found: what it is (e.g. "OpenImageIO's module"),
// where it was looked for, the variable that moves it, and a note for the user (may be empty).
std::string pluginModuleNotFound(const std::string& what, const PluginModuleSearch& search,
                                 const std::string& tried, const std::string& note);

}  // namespace prism
