// The layering, read from the includes: which folder may use which. It fails, naming the file,
// line and include, when one crosses a forbidden edge, so the architecture cannot rot silently
// (docs/architecture.md draws the same layers).
//   common/ (the core and its transport) knows nothing of master/, slave/ or gui/;
//   the core (common/ less common/transport/) includes no transport header;
//   Qt only in gui/; MPI only in common/transport/MpiSession.cpp;
//   master/ and slave/ never include each other (main.cpp, the composition root, may);
//   the wire format does not reach the acceleration structures, even through other headers;
//   the folders of common/ form no cycle.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace prism {
namespace {

namespace fs = std::filesystem;

struct Include {
  std::string file;  // relative to the root, e.g. "common/wire/Messages.h"
  int line = 0;
  std::string target;    // as written
  bool system = false;   // <...>
  std::string resolved;  // the project file it names, relative to the root; "" if none
};

// Every #include of the project's sources under root, resolved the way the build resolves them
// (common/ and the root are the include directories).
class IncludeGraph {
 public:
  explicit IncludeGraph(const fs::path& root) : root_(root) {
    for (const char* top : {"common", "master", "slave", "gui"}) {
      if (!fs::exists(root / top)) continue;
      for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp")) read(entry.path());
      }
    }
  }

  const std::vector<Include>& includes() const { return includes_; }

  // The folder a file belongs to: common/<sub> inside the core, else its top folder.
  static std::string folderOf(const std::string& file) {
    const size_t first = file.find('/');
    if (file.compare(0, first, "common") == 0) {
      const size_t second = file.find('/', first + 1);
      return file.substr(0, second);
    }
    return file.substr(0, first);
  }

  // Project files a file reaches through its includes, itself excluded.
  std::set<std::string> reachable(const std::string& file) const {
    std::set<std::string> seen;
    std::vector<std::string> stack{file};
    while (!stack.empty()) {
      const std::string next = stack.back();
      stack.pop_back();
      const auto it = edges_.find(next);
      if (it == edges_.end()) continue;
      for (const std::string& to : it->second) {
        if (seen.insert(to).second) stack.push_back(to);
      }
    }
    return seen;
  }

 private:
  void read(const fs::path& path) {
    static const std::regex includeLine(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
    const std::string file = fs::relative(path, root_).generic_string();
    std::ifstream in(path);
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
      std::smatch m;
      if (!std::regex_search(text, m, includeLine)) continue;
      Include inc{file, line, m[2].str(), m[1].str() == "<", ""};
      if (!inc.system) {
        for (const fs::path& base : {root_ / "common", root_}) {
          if (fs::exists(base / inc.target)) {
            inc.resolved = fs::relative(base / inc.target, root_).generic_string();
            edges_[file].insert(inc.resolved);
            break;
          }
        }
      }
      includes_.push_back(inc);
    }
  }

  fs::path root_;
  std::vector<Include> includes_;
  std::map<std::string, std::set<std::string>> edges_;
};

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

std::string where(const Include& inc) {
  return inc.file + ":" + std::to_string(inc.line) + ": #include " +
         (inc.system ? "<" + inc.target + ">" : "\"" + inc.target + "\"");
}

// The include edges that break a rule, one line each.
using Rule = std::function<bool(const Include&)>;
std::string violations(const IncludeGraph& graph, const Rule& forbidden) {
  std::string found;
  for (const Include& inc : graph.includes()) {
    if (forbidden(inc)) found += where(inc) + "\n";
  }
  return found;
}

bool isQt(const Include& inc) {
  return inc.system && (std::regex_match(inc.target, std::regex("Q[A-Z][A-Za-z]*")) ||
                        startsWith(inc.target, "Qt"));
}

// The folders of common/ and their include edges; a cycle, if any, as "a -> b -> a".
std::string folderCycle(const IncludeGraph& graph) {
  std::map<std::string, std::set<std::string>> folders;
  for (const Include& inc : graph.includes()) {
    if (inc.resolved.empty() || !startsWith(inc.file, "common/")) continue;
    const std::string from = IncludeGraph::folderOf(inc.file);
    const std::string to = IncludeGraph::folderOf(inc.resolved);
    if (from != to) folders[from].insert(to);
  }
  std::map<std::string, int> state;  // 0 new, 1 on the path, 2 done
  std::vector<std::string> path;
  std::string cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& f) {
    state[f] = 1;
    path.push_back(f);
    for (const std::string& to : folders[f]) {
      if (state[to] == 1) {
        for (auto it = std::find(path.begin(), path.end(), to); it != path.end(); ++it)
          cycle += *it + " -> ";
        cycle += to;
        return true;
      }
      if (state[to] == 0 && visit(to)) return true;
    }
    path.pop_back();
    state[f] = 2;
    return false;
  };
  for (const auto& [f, _] : folders) {
    if (state[f] == 0 && visit(f)) break;
  }
  return cycle;
}

const IncludeGraph& project() {
  static const IncludeGraph graph(PRISM_SOURCE_DIR);
  return graph;
}

TEST(Layering, TheSourcesAreFound) {
  EXPECT_GT(project().includes().size(), 500u);  // a wrong root would pass every rule
}

TEST(Layering, CommonKnowsNothingOfMasterSlaveOrGui) {
  EXPECT_EQ(violations(project(),
                       [](const Include& inc) {
                         return startsWith(inc.file, "common/") &&
                                (startsWith(inc.resolved, "master/") ||
                                 startsWith(inc.resolved, "slave/") ||
                                 startsWith(inc.resolved, "gui/"));
                       }),
            "");
}

TEST(Layering, TheCoreIncludesNoTransport) {
  EXPECT_EQ(violations(project(),
                       [](const Include& inc) {
                         return startsWith(inc.file, "common/") &&
                                !startsWith(inc.file, "common/transport/") &&
                                startsWith(inc.resolved, "common/transport/");
                       }),
            "");
}

TEST(Layering, QtOnlyInGui) {
  EXPECT_EQ(
      violations(project(),
                 [](const Include& inc) { return isQt(inc) && !startsWith(inc.file, "gui/"); }),
      "");
}

TEST(Layering, MpiOnlyInTheMpiTransport) {
  EXPECT_EQ(violations(project(),
                       [](const Include& inc) {
                         return inc.system &&
                                (inc.target == "mpi.h" || startsWith(inc.target, "mpi")) &&
                                inc.file != "common/transport/MpiSession.cpp";
                       }),
            "");
  // The session's header hides MPI, and only main.cpp may name it.
  EXPECT_EQ(violations(project(),
                       [](const Include& inc) {
                         return inc.resolved == "common/transport/MpiSession.h" &&
                                inc.file != "master/main.cpp" &&
                                !startsWith(inc.file, "common/transport/");
                       }),
            "");
}

TEST(Layering, MasterAndSlaveNeverIncludeEachOther) {
  EXPECT_EQ(
      violations(project(),
                 [](const Include& inc) {
                   if (inc.file == "master/main.cpp") return false;  // the composition root
                   return (startsWith(inc.file, "master/") && startsWith(inc.resolved, "slave/")) ||
                          (startsWith(inc.file, "slave/") && (startsWith(inc.resolved, "master/") ||
                                                              startsWith(inc.resolved, "gui/")));
                 }),
      "");
}

// The one exception: the built geometry's wire form (wire/GeometryCodec.h, rank 0's geometry
// broadcast) names the acceleration structures, and Messages.cpp, which instantiates its
// codec, includes it; a header that includes neither (Messages.h declares SceneGeometry only)
// keeps the other messages' users away from them.
TEST(Layering, TheWireFormatDoesNotReachTheAccelerationStructures) {
  std::string found;
  for (const Include& inc : project().includes()) {
    if (!startsWith(inc.file, "common/wire/") || inc.resolved.empty()) continue;
    if (startsWith(inc.file, "common/wire/GeometryCodec.") ||
        inc.file == "common/wire/Messages.cpp") {
      continue;
    }
    for (const std::string& reached : project().reachable(inc.file)) {
      if (startsWith(reached, "common/accel/")) found += inc.file + " reaches " + reached + "\n";
    }
  }
  std::set<std::string> unique;  // one line per pair
  std::string lines;
  size_t start = 0;
  while (start < found.size()) {
    const size_t end = found.find('\n', start);
    if (unique.insert(found.substr(start, end - start)).second)
      lines += found.substr(start, end - start + 1);
    start = end + 1;
  }
  EXPECT_EQ(lines, "");
}

TEST(Layering, TheFoldersOfCommonFormNoCycle) {
  EXPECT_EQ(folderCycle(project()), "");
}

// The layer order docs/architecture.md draws, top first: a folder includes only folders of a
// lower layer (folders of one layer never include each other). master/main.cpp, the
// composition root, stands above all and may include anything.
int layerOf(const std::string& folder) {
  static const std::map<std::string, int> layers = {
      {"gui", 16},  // beside the commands: it is handed to them (master/live/ViewerRunner.h)
      {"master/commands", 16},
      {"master/analysis", 15},
      {"master/remote", 15},
      {"master/live", 14},
      {"master/frame", 13},
      {"master/dispatch", 12},
      {"slave", 12},
      {"common/wire", 10},
      {"common/cluster", 9},
      {"common/render", 8},
      {"common/caustics", 7},
      {"common/shading", 6},
      {"common/parse", 6},
      {"common/scene", 5},
      {"common/accel", 4},
      {"common/geometry", 3},
      {"common/image", 3},
      {"common/transport", 2},
      {"common/math", 1},
      {"common/util", 1},
  };
  const auto it = layers.find(folder);
  return it == layers.end() ? -1 : it->second;
}

std::string layerFolderOf(const std::string& file) {
  const size_t first = file.find('/');
  const std::string top = file.substr(0, first);
  if (top == "common" || top == "master") return file.substr(0, file.find('/', first + 1));
  return top;
}

std::string layerViolations(const IncludeGraph& graph) {
  std::string found;
  for (const Include& inc : graph.includes()) {
    if (inc.resolved.empty() || inc.file == "master/main.cpp") continue;
    const std::string from = layerFolderOf(inc.file);
    const std::string to = layerFolderOf(inc.resolved);
    if (from == to) continue;
    const int fromLayer = layerOf(from);
    const int toLayer = layerOf(to);
    if (fromLayer < 0) {
      found += inc.file + ": in a folder with no layer (add it to layerOf and the drawing)\n";
    } else if (toLayer < 0 || toLayer >= fromLayer) {
      found += where(inc) + "  (" + from + " may not include " + to + ")\n";
    }
  }
  return found;
}

TEST(Layering, EveryFolderIncludesOnlyTheLayersBelowIt) {
  EXPECT_EQ(layerViolations(project()), "");
}

TEST(Layering, MasterNeverIncludesGui) {
  EXPECT_EQ(violations(project(),
                       [](const Include& inc) {
                         return startsWith(inc.file, "master/") && inc.file != "master/main.cpp" &&
                                startsWith(inc.resolved, "gui/");
                       }),
            "");
}

// The checker itself: a planted tree with one of each violation is caught.
TEST(Layering, APlantedViolationOfEachKindIsFound) {
  const fs::path root = fs::temp_directory_path() / "prism-layering-test";
  fs::remove_all(root);
  const auto write = [&](const std::string& file, const std::string& text) {
    fs::create_directories((root / file).parent_path());
    std::ofstream(root / file) << text;
  };
  write("common/a/A.h", "#include \"b/B.h\"\n#include <QWidget>\n");
  write("common/b/B.h", "#include \"a/A.h\"\n#include \"master/M.h\"\n");
  write("common/wire/W.h", "#include \"b/B.h\"\n");
  write("common/accel/Bvh.h", "");
  write("common/b/C.h", "#include \"accel/Bvh.h\"\n#include <mpi.h>\n");
  write("master/M.h", "#include \"slave/S.h\"\n");
  write("slave/S.h", "");
  std::ofstream(root / "common/b/B.h", std::ios::app) << "#include \"b/C.h\"\n";
  const IncludeGraph graph(root);
  EXPECT_NE(folderCycle(graph), "");
  EXPECT_NE(
      violations(graph, [](const Include& i) { return isQt(i) && !startsWith(i.file, "gui/"); }),
      "");
  EXPECT_EQ(graph.reachable("common/wire/W.h").count("common/accel/Bvh.h"), 1u);
  EXPECT_NE(violations(graph,
                       [](const Include& i) {
                         return startsWith(i.file, "master/") && startsWith(i.resolved, "slave/");
                       }),
            "");
  EXPECT_NE(violations(graph,
                       [](const Include& i) {
                         return startsWith(i.file, "common/") && startsWith(i.resolved, "master/");
                       }),
            "");
  fs::remove_all(root);

  // Upward edges: the dispatcher naming the frame's passes, the viewer's pipeline naming a
  // command, and the scene naming the renderer; the downward ones beside them pass.
  write("master/dispatch/D.h", "#include \"master/frame/F.h\"\n");
  write("master/frame/F.h", "#include \"master/dispatch/D2.h\"\n");
  write("master/dispatch/D2.h", "");
  write("master/live/L.h", "#include \"master/commands/C.h\"\n#include \"master/frame/F.h\"\n");
  write("master/commands/C.h", "#include \"master/live/L2.h\"\n");
  write("master/live/L2.h", "");
  write("common/scene/S.h", "#include \"render/T.h\"\n");
  write("common/render/T.h", "#include \"scene/S2.h\"\n");
  write("common/scene/S2.h", "");
  const IncludeGraph upward(root);
  std::string found = layerViolations(upward);
  // One line per violation, in any order the directory walk gives.
  std::multiset<std::string> lines;
  for (size_t start = 0, end; start < found.size(); start = end + 1) {
    end = found.find('\n', start);
    lines.insert(found.substr(start, end - start));
  }
  EXPECT_EQ(lines,
            (std::multiset<std::string>{
                "common/scene/S.h:1: #include \"render/T.h\"  (common/scene may not include "
                "common/render)",
                "master/dispatch/D.h:1: #include \"master/frame/F.h\"  (master/dispatch may not "
                "include master/frame)",
                "master/live/L.h:1: #include \"master/commands/C.h\"  (master/live may not include "
                "master/commands)",
            }));
  fs::remove_all(root);
}

}  // namespace
}  // namespace prism
