#include "parse/GltfUri.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace prism {
namespace {

std::string text(const std::vector<uint8_t>& bytes) {
  return {bytes.begin(), bytes.end()};
}

TEST(GltfUri, Base64DecodesWithAndWithoutPadding) {
  EXPECT_EQ(text(decodeBase64("TWFu")), "Man");
  EXPECT_EQ(text(decodeBase64("TWE=")), "Ma");
  EXPECT_EQ(text(decodeBase64("TWE")), "Ma");
  EXPECT_EQ(text(decodeBase64("TQ==")), "M");
  EXPECT_EQ(text(decodeBase64("")), "");
  EXPECT_EQ(base64DecodedSize("TWFuTQ=="), 4u);
}

TEST(GltfUri, Base64NamesTheFirstBadCharacter) {
  try {
    decodeBase64("TWFu T==");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "' ' at character 4 is not base64");
  }
  EXPECT_THROW(decodeBase64("TWFuT"), std::invalid_argument);
}

TEST(GltfUri, DataUrisSplitIntoTypeAndPayload) {
  const std::optional<DataUri> d = splitDataUri("data:image/png;base64,AAAA");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->mediaType, "image/png");
  EXPECT_EQ(d->payload, "AAAA");
  EXPECT_FALSE(splitDataUri("mesh.bin"));
  EXPECT_THROW(splitDataUri("data:text/plain,hello"), std::invalid_argument);
}

TEST(GltfUri, RelativeUrisArePercentDecodedAndOthersRefused) {
  EXPECT_EQ(uriToRelativePath("tex/a%20b.png"), "tex/a b.png");
  EXPECT_EQ(uriToRelativePath("../x.bin"), "../x.bin");
  EXPECT_THROW(uriToRelativePath("http://example.com/a.bin"), std::invalid_argument);
  EXPECT_THROW(uriToRelativePath("/etc/passwd"), std::invalid_argument);
}

}  // namespace
}  // namespace prism
