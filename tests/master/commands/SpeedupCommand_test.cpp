// End to end: `mpiexec -n 3 prism speedup` on a tiny scene writes a table, the CSVs with one
// row per point, and (with Qt) two chart images.
#include "master/commands/SpeedupCommand.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "master/PrismProcess.h"
#include "master/analysis/SpeedupReport.h"

namespace prism {
namespace {

using test::runPrism;
using test::runPrismMpi;

class SpeedupCommand : public test::ScratchFolderTest {};

std::vector<std::vector<std::string>> csvRows(const std::string& path) {
  std::ifstream file(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream in(line);
    std::string field;
    while (std::getline(in, field, ',')) fields.push_back(field);
    if (line.back() == ',') fields.push_back("");
    rows.push_back(fields);
  }
  return rows;
}

// A PNG's width and height from its IHDR chunk; 0 when the file is not a PNG.
std::pair<uint32_t, uint32_t> pngSize(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  unsigned char head[24] = {};
  file.read(reinterpret_cast<char*>(head), sizeof head);
  if (!file || head[1] != 'P' || head[2] != 'N' || head[3] != 'G') return {0, 0};
  const auto be32 = [&](int at) {
    return uint32_t{head[at]} << 24 | uint32_t{head[at + 1]} << 16 | uint32_t{head[at + 2]} << 8 |
           head[at + 3];
  };
  return {be32(16), be32(20)};
}

TEST_F(SpeedupCommand, ThreeRanksWriteEveryPointChartsAndProjection) {
  const std::string prefix = path("run");
  const test::ProcessRun run =
      runPrismMpi(3,
                  "speedup " + std::string(PRISM_SOURCE_DIR) +
                      "/scenes/lambert-plane.yaml -W 64 -H 48 -s 1 --tile-sizes 16 -r 2 "
                      "--project-workers 16 -q -o " +
                      prefix,
                  "--bind-to none");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("T1 (1 process, 1 thread, no MPI)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Karp"), std::string::npos);
  // Rank 0's start is accounted for apart from the set-up, with MPI_Init measured (not zero).
  const size_t start = run.output.find("start (rank 0, before the command): launch ");
  ASSERT_NE(start, std::string::npos) << run.output;
  const size_t init = run.output.find("of which MPI_Init ", start);
  ASSERT_NE(init, std::string::npos) << run.output;
  EXPECT_GT(std::stod(run.output.substr(init + std::string("of which MPI_Init ").size())), 0.0);
  // The slaves' own starts come with their Ready.
  const size_t slaveStart =
      run.output.find("start (slowest slave, before its command): process start to command ");
  ASSERT_NE(slaveStart, std::string::npos) << run.output;
  const size_t slaveInit = run.output.find(" s, MPI_Init ", slaveStart);
  ASSERT_NE(slaveInit, std::string::npos) << run.output;
  EXPECT_GT(std::stod(run.output.substr(slaveInit + std::string(" s, MPI_Init ").size())), 0.0);
  // Every rank is on this machine: a sender's ring ends a wait (MpiSession's doorbells).
  EXPECT_NE(run.output.find("; waits woken by the sender (and a probe every 1 ms)\n"),
            std::string::npos)
      << run.output;

  EXPECT_NE(run.output.find("  kernels: x86-64"), std::string::npos) << run.output;

  const SpeedupOutputs files = speedupOutputs(prefix);
  {
    std::ifstream csv(files.csv);
    const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\n# kernels: x86-64"), std::string::npos) << text;
  }
  const auto rows = csvRows(files.csv);
  ASSERT_EQ(rows.size(), 1u + 2 * 2) << "header + 2 schedules x p = 1, 2";
  EXPECT_EQ(rows[0], speedupCsvColumns());
  const auto column = [&](const char* name) {
    return static_cast<size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const char* expected[][2] = {
      {"dynamic", "1"}, {"dynamic", "2"}, {"static", "1"}, {"static", "2"}};
  for (size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), rows[0].size()) << i;
    EXPECT_EQ(rows[i][column("schedule")], expected[i - 1][0]);
    EXPECT_EQ(rows[i][column("p")], expected[i - 1][1]);
    EXPECT_GT(std::stod(rows[i][column("seconds")]), 0.0);
    EXPECT_GT(std::stod(rows[i][column("speedup")]), 0.0);
    EXPECT_GT(std::stod(rows[i][column("model_seconds")]), 0.0);
    EXPECT_NEAR(std::stod(rows[i][column("efficiency")]),
                std::stod(rows[i][column("speedup")]) / std::stod(rows[i][column("p")]), 1e-4);
    const int cores = static_cast<int>(std::thread::hardware_concurrency());
    EXPECT_EQ(rows[i][column("oversubscribed")],
              std::stoi(rows[i][column("p")]) + 1 > cores ? "yes" : "no");
  }
  // 4 image sizes x p = 1, 2, 4, 8, 16 x 2 schedules, and a header.
  EXPECT_EQ(csvRows(files.projectionCsv).size(), 1u + 4 * 5 * 2);
#ifdef PRISM_HAVE_VIEWER
  for (const std::string& chart : {files.chart, files.projectionChart}) {
    const auto [width, height] = pngSize(chart);
    EXPECT_EQ(width, 2000u) << chart;
    EXPECT_EQ(height, 640u) << chart;
    EXPECT_GT(std::filesystem::file_size(chart), 20000u) << chart;  // axes, lines, text
  }
#else
  EXPECT_NE(run.output.find("the charts need Qt5 Charts"), std::string::npos);
#endif
}

TEST_F(SpeedupCommand, WithoutAnMpiJobItSaysHowToStartOne) {
  const test::ProcessRun run =
      runPrism("speedup " + std::string(PRISM_SOURCE_DIR) + "/scenes/lambert-plane.yaml");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("mpiexec -n N prism speedup"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace prism
