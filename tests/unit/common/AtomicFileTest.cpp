#include "core/common/AtomicFile.h"

#include "core/common/Error.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>

using namespace scanpick;

TEST(AtomicFile, WritesAndReadsBack) {
  test::TempDir dir;
  core::writeFileAtomic(dir / "a.txt", "hello");
  EXPECT_EQ(core::readFile(dir / "a.txt"), "hello");
  core::writeFileAtomic(dir / "a.txt", "replaced");
  EXPECT_EQ(core::readFile(dir / "a.txt"), "replaced");
  EXPECT_EQ(test::fileCount(dir.path()), 1u) << "no temporary file may be left behind";
}

TEST(AtomicFile, FailedWriteKeepsOldContentAndLeavesNoTemporary) {
  test::TempDir dir;
  core::writeFileAtomic(dir / "a.txt", "original");
  EXPECT_THROW(core::writeFileAtomicWith(dir / "a.txt",
                                         [](const std::filesystem::path& tmp) {
                                           core::writeFileAtomic(tmp, "half");
                                           throw core::Error("disk full");
                                         }),
               core::Error);
  EXPECT_EQ(core::readFile(dir / "a.txt"), "original");
  EXPECT_EQ(test::fileCount(dir.path()), 1u);
}

TEST(AtomicFile, MissingFolderIsAClearError) {
  test::TempDir dir;
  try {
    core::writeFileAtomic(dir / "no/such/folder/a.txt", "x");
    FAIL() << "expected an error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_THROW(core::readFile(dir / "missing.txt"), core::Error);
}
