#include "grid/file_path.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace grid {
namespace {

namespace fs = std::filesystem;

// A folder `real/` holding maps/m.yaml, and `link` -> real beside it: a checkout and the
// symbolic link a catkin workspace reaches it through.
class FilePathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
    dir_ = fs::temp_directory_path() / ("grid_file_path_test_" + std::to_string(unit.random_seed()) + "_" +
                                        unit.current_test_info()->name());
    fs::create_directories(dir_ / "real" / "maps");
    std::ofstream(dir_ / "real" / "maps" / "m.yaml") << "image: m.pgm\n";
    fs::create_directory_symlink(dir_ / "real", dir_ / "link");
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

TEST_F(FilePathTest, AFileThroughALinkAndThroughItsRealPathIsOnePath) {
  const std::string real = CanonicalPath((dir_ / "real" / "maps" / "m.yaml").string());
  EXPECT_EQ(CanonicalPath((dir_ / "link" / "maps" / "m.yaml").string()), real);
  EXPECT_EQ(CanonicalPath((dir_ / "link" / "maps" / ".." / "maps" / "m.yaml").string()), real);
  EXPECT_TRUE(fs::path(real).is_absolute());
  EXPECT_EQ(real.find("link"), std::string::npos) << real;
}

TEST_F(FilePathTest, AFileNotYetWrittenResolvesAsFarAsItsFolderExists) {
  EXPECT_EQ(CanonicalPath((dir_ / "link" / "maps" / "new.yaml").string()),
            CanonicalPath((dir_ / "real" / "maps" / "new.yaml").string()));
  EXPECT_EQ(CanonicalPath((dir_ / "link" / "no_such" / "x.yaml").string()),
            (fs::canonical(dir_ / "real") / "no_such" / "x.yaml").string());
}

TEST_F(FilePathTest, ARelativePathIsMadeAbsoluteFromTheWorkingDirectory) {
  const fs::path before = fs::current_path();
  fs::current_path(dir_ / "link");
  const std::string relative = CanonicalPath("maps/m.yaml");
  const std::string missing = CanonicalPath("nothing/here.yaml");
  fs::current_path(before);
  EXPECT_EQ(relative, CanonicalPath((dir_ / "real" / "maps" / "m.yaml").string()));
  EXPECT_EQ(missing, (fs::canonical(dir_ / "real") / "nothing" / "here.yaml").string());
}

TEST(FilePath, NoPathStaysNoPath) { EXPECT_EQ(CanonicalPath(""), ""); }

// A world file may name anything as its map; a name longer than the file system allows made
// weakly_canonical throw, and the world loader die on it (found by fuzz_world_file).
TEST(FilePath, UnresolvableNameIsKeptAsWritten) {
  const std::string too_long = "/tmp/" + std::string(300, 'x') + "/../m.yaml";
  std::string result;
  ASSERT_NO_THROW(result = CanonicalPath(too_long));
  EXPECT_EQ(result, "/tmp/m.yaml");
}

}  // namespace
}  // namespace grid
