// Point cloud files that are damaged, foreign or hostile: each one gets a clear Error that names
// the file, never a crash, a hang or points read as zeros; well-formed files in every encoding
// and coordinate type are read exactly.
#include "core/cloud/CloudIo.h"
#include "core/cloud/PcdFile.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "tests/support/TempDir.h"

#include <csignal>
#include <cstring>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/lzf.h>
#include <sys/resource.h>

using namespace scanpick;
using ::testing::HasSubstr;

namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string loadError(const test::TempDir& dir, const std::string& name, const std::string& bytes) {
  core::writeFileAtomic(dir / name, bytes);
  return errorOf([&] { core::loadCloud(dir / name, core::LengthUnit::Millimetres); });
}

std::string header(const std::string& fields, const std::string& size, const std::string& type,
                   const std::string& count, const std::string& width, const std::string& height,
                   const std::string& data) {
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type + "\nCOUNT " +
         count + "\nWIDTH " + width + "\nHEIGHT " + height + "\nVIEWPOINT 0 0 0 1 0 0 0\nDATA " +
         data + "\n";
}

template <typename T> std::string binary(std::initializer_list<T> values) {
  std::string out(values.size() * sizeof(T), '\0');
  std::memcpy(out.data(), values.begin(), out.size());
  return out;
}

} // namespace

TEST(BadCloudFiles, FilesThatAreNotPcdAreRefusedByName) {
  test::TempDir dir;
  EXPECT_THAT(loadError(dir, "text.pcd", "hello, this is a note\nnot a cloud\n"),
              HasSubstr("text.pcd"));
  EXPECT_THAT(loadError(dir, "png.pcd", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)),
              HasSubstr("not a PCD file"));
  EXPECT_THAT(loadError(dir, "byte.pcd", "x"), HasSubstr("not a PCD file"));
  const std::string misspelled =
      "VERSION 0.7\nFIELSD x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA ascii\n1 2 3\n";
  EXPECT_THAT(loadError(dir, "misspelled.pcd", misspelled), HasSubstr("FIELSD"));
}

TEST(BadCloudFiles, HugeDeclaredSizesAreRefusedBeforeAllocating) {
  test::TempDir dir;
  EXPECT_THAT(
      loadError(dir, "wide.pcd",
                header("x y z", "4 4 4", "F F F", "1 1 1", "2147483648", "2147483648", "binary") +
                    binary<float>({1, 2, 3})),
      HasSubstr("WIDTH"));
  EXPECT_THAT(loadError(dir, "grid.pcd",
                        header("x y z", "4 4 4", "F F F", "1 1 1", "65536", "65536", "binary")),
              HasSubstr("more than scanpick reads"));
  EXPECT_THAT(loadError(dir, "count.pcd",
                        header("x y z", "4 4 4", "F F F", "1 2147483647 1", "1", "1", "binary")),
              HasSubstr("COUNT"));
  EXPECT_THAT(loadError(dir, "short.pcd",
                        header("x y z", "4 4 4", "F F F", "1 1 1", "1000", "1", "binary") +
                            binary<float>({1, 2, 3})),
              HasSubstr("truncated"));
  EXPECT_THAT(
      loadError(dir, "ascii-short.pcd",
                header("x y z", "4 4 4", "F F F", "1 1 1", "1000000", "1", "ascii") + "1 2 3\n"),
      HasSubstr("truncated"));
}

TEST(BadCloudFiles, DoubleCoordinatesAreReadAndIntegerOnesRefused) {
  test::TempDir dir;
  core::writeFileAtomic(dir / "double.pcd",
                        header("x y z", "8 8 8", "F F F", "1 1 1", "2", "1", "binary") +
                            binary<double>({0.25, -1.5, 0.75, 1e-3, 2e-3, 0.5}));
  const auto loaded = core::loadCloud(dir / "double.pcd", core::LengthUnit::Metres);
  ASSERT_EQ(loaded.cloud.size(), 2u);
  EXPECT_TRUE(loaded.cloud.points_mm[0].isApprox(Eigen::Vector3f(250, -1500, 750)));
  EXPECT_TRUE(loaded.cloud.points_mm[1].isApprox(Eigen::Vector3f(1, 2, 500)));
  EXPECT_THAT(loadError(dir, "uint8.pcd",
                        header("x y z", "1 1 1", "U U U", "1 1 1", "1", "1", "binary") + "abc"),
              HasSubstr("unsigned integers"));
}

TEST(BadCloudFiles, MalformedAsciiDataIsRefusedWithItsLine) {
  test::TempDir dir;
  const std::string head = header("x y z", "4 4 4", "F F F", "1 1 1", "2", "1", "ascii");
  EXPECT_THAT(loadError(dir, "word.pcd", head + "1 2 3\n4 five 6\n"),
              HasSubstr("data line 2: 'five' is not a number"));
  EXPECT_THAT(loadError(dir, "fields.pcd", head + "1 2 3\n4 5\n"),
              HasSubstr("data line 2 has 2 values"));
  core::writeFileAtomic(dir / "good.pcd", head + "1 2 3\nnan nan nan\n");
  const auto good = core::loadCloud(dir / "good.pcd", core::LengthUnit::Millimetres);
  EXPECT_EQ(good.cloud.validCount(), 1u);
}

TEST(BadCloudFiles, AFlippedBitInACoordinateMakesAnInvalidPointAndAWarning) {
  test::TempDir dir;
  core::writeFileAtomic(dir / "flip.pcd",
                        header("x y z", "4 4 4", "F F F", "1 1 1", "3", "1", "binary") +
                            binary<float>({10, 20, 700, 1.67e20f, 20, 700, 11, 21,
                                           std::numeric_limits<float>::infinity()}));
  const auto loaded = core::loadCloud(dir / "flip.pcd", core::LengthUnit::Millimetres);
  EXPECT_EQ(loaded.cloud.validCount(), 1u);
  EXPECT_THAT(loaded.units_warning, HasSubstr("2 point(s) lie farther than"));
}

TEST(BadCloudFiles, CompressedPcdIsReadFieldByField) {
  // binary_compressed stores each field for all points in turn (x x, y y, z z), LZF-compressed.
  const std::string raw = binary<float>({1, 4, 2, 5, 3, 6});
  std::string packed(raw.size() * 2 + 16, '\0');
  const unsigned int size = pcl::lzfCompress(raw.data(), static_cast<unsigned>(raw.size()),
                                             packed.data(), static_cast<unsigned>(packed.size()));
  ASSERT_GT(size, 0u);
  const std::string bytes =
      header("x y z", "4 4 4", "F F F", "1 1 1", "2", "1", "binary_compressed") +
      binary<std::uint32_t>({size, static_cast<std::uint32_t>(raw.size())}) +
      packed.substr(0, size);
  const core::PointCloud cloud = core::decodePcd(bytes, "c.pcd");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_TRUE(cloud.points_mm[0].isApprox(Eigen::Vector3f(1, 2, 3)));
  EXPECT_TRUE(cloud.points_mm[1].isApprox(Eigen::Vector3f(4, 5, 6)));
  std::string lying = bytes;
  lying[lying.size() - size - 4] ^= 0x10; // the uncompressed size no longer matches the points
  EXPECT_THAT(errorOf([&] { core::decodePcd(lying, "c.pcd"); }), HasSubstr("does not match"));
}

TEST(BadCloudFiles, PlyDeclaringMoreElementsThanItHoldsIsRefusedAtOnce) {
  test::TempDir dir;
  const std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex "
                          "18446744073709551615\nproperty float x\nproperty float y\nproperty "
                          "float z\nend_header\n" +
                          binary<float>({1, 2, 3});
  EXPECT_THAT(loadError(dir, "huge.ply", ply), HasSubstr("more than the file's 12 bytes"));
  EXPECT_THAT(loadError(dir, "noprops.ply",
                        "ply\nformat ascii 1.0\nelement vertex 5\nelement face "
                        "18446744073709551615\nend_header\n"),
              HasSubstr("no properties"));
}

TEST(BadCloudFiles, PlyRoundTripsWithNormalsAndColours) {
  test::TempDir dir;
  core::PointCloud cloud = core::PointCloud::fromPoints({{1, 2, 3}, {4, 5, 6}});
  cloud.normals = {{0, 0, 1}, {1, 0, 0}};
  cloud.colors = {{{10, 20, 30}}, {{40, 50, 60}}};
  core::saveCloudPly(dir / "c.ply", cloud);
  const auto loaded = core::loadCloud(dir / "c.ply", core::LengthUnit::Millimetres).cloud;
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_TRUE(loaded.points_mm[1].isApprox(cloud.points_mm[1]));
  EXPECT_TRUE(loaded.normals[1].isApprox(cloud.normals[1]));
  EXPECT_EQ(loaded.colors[0], cloud.colors[0]);
}

TEST(BadCloudFiles, AWriteThatFailsLeavesTheGoodFileAndNoTemporary) {
  test::TempDir dir;
  const core::PointCloud small = core::PointCloud::fromPoints({{1, 2, 3}});
  core::saveCloudPcd(dir / "scan.pcd", small);
  const std::string good = core::readFile(dir / "scan.pcd");
  // A disk that fills: the file size limit makes writes fail with EFBIG as ENOSPC would.
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit limited = old;
  limited.rlim_cur = 4096;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
  const std::string message = errorOf([&] {
    core::saveCloudPcd(dir / "scan.pcd",
                       core::PointCloud::fromPoints(std::vector<Eigen::Vector3f>(10000)));
  });
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &old), 0);
  EXPECT_THAT(message, HasSubstr("scan.pcd"));
  EXPECT_EQ(core::readFile(dir / "scan.pcd"), good);
  EXPECT_EQ(test::fileCount(dir.path()), 1u) << "a temporary file was left behind";
}
