// Runs the real prism executable (optionally under mpiexec) for end-to-end tests, and gives
// each test its own scratch folder.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace prism::test {

struct ProcessRun {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

inline ProcessRun runCommand(const std::string& command) {
  ProcessRun run;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    run.output.append(buffer.data(), n);
  }
  const int status = ::pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

inline ProcessRun runPrism(const std::string& arguments) {
  return runCommand(std::string(PRISM_EXECUTABLE) + " " + arguments);
}

// Runs prism on `ranks` MPI processes. Open MPI refuses root without two variables and more
// ranks than cores without --oversubscribe: the test sets both (prepareMpiEnvironment), the user
// never has to. The
// timeout bounds a run that would otherwise hang the suite.
// What every mpiexec a test starts needs in its environment. Open MPI refuses root without two
// variables. And Open MPI 4 keeps its session directories under one folder per user in /tmp,
// which concurrent jobs (ctest -j) create and remove at once: a job starting as another ends can
// fail in orte_init with "File exists" (open-mpi/ompi#7049, #8510). Each test process gives its
// jobs a folder of their own, removed when the process ends.
inline void prepareMpiEnvironment() {
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  struct SessionFolder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("prism-ompi-" + std::to_string(::getpid()));
    SessionFolder() {
      std::filesystem::create_directories(path);
      ::setenv("OMPI_MCA_orte_tmpdir_base", path.c_str(), 1);
    }
    ~SessionFolder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const SessionFolder folder;
}

inline ProcessRun runPrismMpi(int ranks, const std::string& arguments,
                              const std::string& mpiexecOptions = "") {
  prepareMpiEnvironment();
  return runCommand("timeout 120 mpiexec -n " + std::to_string(ranks) + " --oversubscribe " +
                    mpiexecOptions + " " + std::string(PRISM_EXECUTABLE) + " " + arguments);
}

// Runs prism as one MPI job of several programs (MPMD: `mpiexec -n 1 prism A : -n 1 prism B`),
// one rank per entry, each with its own arguments: ranks that differ as uneven nodes do.
inline ProcessRun runPrismMpmd(const std::vector<std::string>& argumentsPerRank,
                               const std::string& mpiexecOptions = "") {
  prepareMpiEnvironment();
  std::string command = "timeout 120 mpiexec --oversubscribe " + mpiexecOptions;
  for (size_t i = 0; i < argumentsPerRank.size(); ++i) {
    command += (i == 0 ? " -n 1 " : " : -n 1 ") + std::string(PRISM_EXECUTABLE) + " " +
               argumentsPerRank[i];
  }
  return runCommand(command);
}

class ScratchFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "-" + info->name();
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    // The process id keeps two runs of the same test (ctest -j, repeated runs) apart.
    dir_ = std::filesystem::temp_directory_path() /
           ("prism-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

}  // namespace prism::test
