#include "util/PluginModule.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace prism {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> candidatePaths(const PluginModuleSearch& search) {
  // The variable, when set, is the only place: it says where the module is, or that it is not.
  if (!search.environmentVariable.empty()) {
    const char* env = std::getenv(search.environmentVariable.c_str());
    if (env && *env) return {env};
  }
  std::vector<std::string> paths;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) paths.push_back((exe.parent_path() / search.fileName).string());
  if (!search.buildPath.empty() && (paths.empty() || paths.front() != search.buildPath)) {
    paths.push_back(search.buildPath);
  }
  return paths;
}

}  // namespace

void* loadPluginModule(const PluginModuleSearch& search,
                       const std::function<bool(void* entry)>& accept, std::string* tried) {
  for (const std::string& path : candidatePaths(search)) {
    if (!fs::exists(path)) {
      *tried += "\n  " + path + " (absent)";
      continue;
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | (search.global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (!handle) {
      const char* why = ::dlerror();
      *tried += "\n  " + path + " (" + (why ? why : "cannot be loaded") + ")";
      continue;
    }
    void* entry = ::dlsym(handle, search.entryName.c_str());
    if (!entry || !accept(entry)) {
      *tried += "\n  " + path + " (not a " + search.fileName + " module of this build)";
      ::dlclose(handle);
      continue;
    }
    return entry;  // never unloaded: the libraries behind it keep threads and caches until exit
  }
  return nullptr;
}

std::string pluginModuleNotFound(const std::string& what, const PluginModuleSearch& search,
                                 const std::string& tried, const std::string& note) {
  return what + " " + search.fileName + " was not found; looked at:" + tried +
         "\n(it is built with prism; set " + search.environmentVariable +
         " to its path if it was moved." + (note.empty() ? "" : " " + note) + ")";
}

}  // namespace prism
