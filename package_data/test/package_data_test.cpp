#include "package_data/package_data.h"

#include <unistd.h>

#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace package_data {
namespace {
namespace fs = std::filesystem;

// A fresh folder under the system's temporary folder, removed at the end.
class TempTree : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("package_data_test." + std::to_string(getpid()) + "." +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    root_ = fs::canonical(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // PREFIX/share/multirobot_audio/package.xml, as an install space has it.
  fs::path MakeShare(const fs::path& prefix) {
    const fs::path share = prefix / "share" / "multirobot_audio";
    fs::create_directories(share);
    std::ofstream(share / "package.xml") << "<package><name>multirobot_audio</name></package>\n";
    return share;
  }

  fs::path root_;
};

TEST_F(TempTree, FindsTheShareFolderOfTheInstallSpaceAProgramIsIn) {
  const fs::path share = MakeShare(root_ / "prefix");
  fs::create_directories(root_ / "prefix" / "lib" / "multirobot_audio");
  EXPECT_EQ(FindShareDirFrom(root_ / "prefix" / "lib" / "multirobot_audio"), share);
  EXPECT_EQ(FindShareDirFrom(root_ / "prefix"), share);
}

TEST_F(TempTree, TheNearestShareFolderWins) {
  MakeShare(root_);
  const fs::path inner = MakeShare(root_ / "build");
  fs::create_directories(root_ / "build" / "nava_modem");
  EXPECT_EQ(FindShareDirFrom(root_ / "build" / "nava_modem"), inner);
}

TEST_F(TempTree, AShareFolderWithoutThePackageIsNotIt) {
  fs::create_directories(root_ / "devel" / "share" / "multirobot_audio" / "cmake");
  fs::create_directories(root_ / "devel" / "lib" / "multirobot_audio");
  EXPECT_FALSE(FindShareDirFrom(root_ / "devel" / "lib" / "multirobot_audio").has_value());
}

TEST_F(TempTree, FoundThroughASymbolicLinkAsTheRealFolder) {
  const fs::path share = MakeShare(root_ / "real");
  fs::create_directories(root_ / "real" / "lib" / "multirobot_audio");
  fs::create_directory_symlink(root_ / "real", root_ / "link");
  EXPECT_EQ(FindShareDirFrom(root_ / "link" / "lib" / "multirobot_audio"), share);
}

TEST_F(TempTree, TheVariableNamesTheShareFolderOutright) {
  const fs::path share = MakeShare(root_ / "elsewhere");
  MakeShare(root_ / "prefix");
  EXPECT_EQ(ResolveShareDir(share.c_str(), root_ / "prefix"), share);
  EXPECT_EQ(ResolveShareDir("", root_ / "prefix"), root_ / "prefix" / "share" / "multirobot_audio");
}

TEST_F(TempTree, AVariableNamingNoPackageIsRefusedByName) {
  try {
    ResolveShareDir((root_ / "nothing").c_str(), root_);
    FAIL() << "no error";
  } catch (const PackageDataError& e) {
    EXPECT_NE(std::string(e.what()).find("MULTIROBOT_AUDIO_SHARE_DIR=" + (root_ / "nothing").string()), std::string::npos)
        << e.what();
  }
}

TEST_F(TempTree, NoShareFolderAnywhereSaysWhereItLooked) {
  fs::create_directories(root_ / "bin");
  try {
    ResolveShareDir(nullptr, root_ / "bin");
    FAIL() << "no error";
  } catch (const PackageDataError& e) {
    EXPECT_NE(std::string(e.what()).find((root_ / "bin").string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace package_data
