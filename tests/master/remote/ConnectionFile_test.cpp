#include "master/remote/ConnectionFile.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "master/remote/AccessToken.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

class ConnectionFile : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("prism-connection-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text, mode_t mode = 0600) {
    const std::string p = path(name);
    std::ofstream(p) << text;
    ::chmod(p.c_str(), mode);
    return p;
  }
  static std::string errorOf(const std::string& file) {
    try {
      readConnectionFile(file);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "accepted";
  }
  fs::path dir_;
};

TEST_F(ConnectionFile, RoundTripsAndIsPrivate) {
  const ConnectionInfo info{{"127.0.0.1", 4050}, newAccessToken(), 1};
  writeConnectionFile(path("job"), info);
  struct stat status {};
  ASSERT_EQ(::stat(path("job").c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0600u);
  const ConnectionInfo read = readConnectionFile(path("job"));
  EXPECT_EQ(read.endpoint.host, "127.0.0.1");
  EXPECT_EQ(read.endpoint.port, 4050);
  EXPECT_EQ(read.token, info.token);
  EXPECT_EQ(read.protocol, 1u);
}

TEST_F(ConnectionFile, AFileOthersMayReadIsRefused) {
  writeConnectionFile(path("job"), {{"127.0.0.1", 4050}, newAccessToken(), 1});
  ::chmod(path("job").c_str(), 0644);
  EXPECT_EQ(errorOf(path("job")),
            "connection file " + path("job") +
                " may be read by others (chmod 600 it): its token is a secret");
}

TEST_F(ConnectionFile, MalformedFilesNameTheLine) {
  const std::string token = std::string(64, 'a');
  EXPECT_EQ(errorOf(write("a", "host=h\nport=99999\n")),
            path("a") + ":2: port '99999' is not a number up to 65535");
  EXPECT_EQ(errorOf(write("b", "host=h\nport=1\ntoken=abc\n")),
            path("b") + ":3: the token is not 64 hex digits");
  EXPECT_EQ(errorOf(write("c", "# comment\nnonsense\n")), path("c") + ":2: expected key=value");
  EXPECT_EQ(errorOf(write("d", "colour=blue\n")), path("d") + ":1: unknown key 'colour'");
  EXPECT_EQ(errorOf(write("e", "host=h\nport=1\nprotocol=1\n")),
            "connection file " + path("e") + " has no token");
  EXPECT_EQ(errorOf(path("missing")).rfind("cannot read connection file " + path("missing"), 0),
            0u);
  EXPECT_EQ(errorOf(write("f", "host=h\nport=1\ntoken=" + token + "\nprotocol=1\n")), "accepted");
}

TEST_F(ConnectionFile, TheTokenComesFromItsFileOrTheEnvironment) {
  const std::string token = newAccessToken();
  EXPECT_EQ(tokenFromFileOrEnvironment(write("t", token + "\n")), token);
  ::setenv("PRISM_TOKEN", "from-env", 1);
  EXPECT_EQ(tokenFromFileOrEnvironment(""), "from-env");
  ::unsetenv("PRISM_TOKEN");
  EXPECT_THROW(tokenFromFileOrEnvironment(""), std::runtime_error);
  EXPECT_THROW(tokenFromFileOrEnvironment(write("empty", "")), std::runtime_error);
}

}  // namespace
}  // namespace prism
