// docs/README.md's how-to sections list the files a new kind of thing touches. These helpers
// read such a list and find the files that name one example of the kind, so a test can check
// the list against the sources: every file that names the example must be listed.
#pragma once

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace prism::howto {

namespace fs = std::filesystem;

inline const fs::path kRoot = PRISM_SOURCE_DIR;

inline std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The files the bullets of docs/README.md's section `heading` begin with ("- `path`: ..."),
// from the heading to the next heading of any level. Empty when there is no such section.
inline std::set<std::string> listedFiles(const std::string& heading) {
  const std::string doc = readFile(kRoot / "docs/README.md");
  const size_t begin = doc.find("\n" + heading + "\n");
  if (begin == std::string::npos) return {};
  const size_t end = doc.find("\n#", begin + heading.size() + 2);
  const std::string section = doc.substr(begin, end - begin);
  std::set<std::string> files;
  static const std::regex bullet(R"(\n- `([^`]+)`:)");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), bullet);
       it != std::sregex_iterator(); ++it) {
    files.insert((*it)[1].str());
  }
  return files;
}

// Sources (.h, .cpp under `sourceTops`) matching `code`, and documents (.md, .yaml under
// `documentTops`, and README.md) matching `document`; paths relative to the repository. Tests,
// docs/README.md (whose how-to names every example) and docs/journal/ are not read.
inline std::set<std::string> filesNaming(const std::regex& code, const std::regex& document,
                                         std::initializer_list<const char*> tops) {
  std::set<std::string> found;
  for (const char* top : tops) {
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      const std::string relative = fs::relative(entry.path(), kRoot).generic_string();
      if (relative == "docs/README.md" || relative.rfind("docs/journal/", 0) == 0) continue;
      const bool isDocument = ext == ".md" || ext == ".yaml";
      if (!isDocument && ext != ".h" && ext != ".cpp") continue;
      const std::string text = readFile(entry.path());
      if (std::regex_search(text, isDocument ? document : code)) found.insert(relative);
    }
  }
  if (std::regex_search(readFile(kRoot / "README.md"), document)) found.insert("README.md");
  return found;
}

}  // namespace prism::howto
