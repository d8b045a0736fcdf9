// FileCamera replay, the registry's id parsing and messages, the capture writer, streaming
// through the Camera base class, and the USB monitor's behaviour with nothing plugged in.
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "devices/CameraRegistry.h"
#include "devices/CaptureWriter.h"
#include "devices/file/FileCamera.h"
#include "devices/usb/UsbMonitor.h"
#include "tests/devices/SyntheticScene.h"
#include "tests/support/TempDir.h"

#include <condition_variable>
#include <gtest/gtest.h>
#include <mutex>
#include <nlohmann/json.hpp>

using namespace scanpick;
using namespace std::chrono_literals;

namespace {

/// Three clouds told apart by a z offset of 0, 10, 20 mm, saved in mm.
void writeSequence(const std::filesystem::path& dir) {
  for (int i = 0; i < 3; ++i)
    core::saveCloudPcd(dir / ("frame-" + std::to_string(i) + ".pcd"),
                       test::syntheticBinScene(40, 30, 40.0, 10.0f * i));
}

devices::DeviceErrorKind kindOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const devices::DeviceError& e) {
    return e.kind();
  }
  ADD_FAILURE() << "no DeviceError";
  return devices::DeviceErrorKind::Unsupported;
}

} // namespace

TEST(FileCamera, ReplaysAFolderInOrderThenEnds) {
  test::TempDir dir;
  writeSequence(dir.path());
  auto camera = devices::openCamera("file:" + dir.path().string());
  const core::PointCloud first = test::syntheticBinScene(40, 30, 40.0);
  for (int i = 0; i < 3; ++i) {
    const devices::Frame f = camera->capture(1000ms);
    ASSERT_TRUE(f.cloud.isOrganized());
    const std::size_t centre = 15 * 40 + 20;
    EXPECT_NEAR(f.cloud.points_mm[centre].z(), first.points_mm[centre].z() + 10.0f * i, 1e-3);
    EXPECT_EQ(f.metadata.frame_index, static_cast<std::uint64_t>(i));
  }
  EXPECT_EQ(kindOf([&] { camera->capture(1000ms); }), devices::DeviceErrorKind::StreamEnded);
}

TEST(FileCamera, MetresAreDetectedAndConverted) {
  test::TempDir dir;
  const core::PointCloud mm = test::syntheticBinScene(40, 30, 40.0);
  core::PointCloud metres = mm;
  for (auto& p : metres.points_mm)
    p /= 1000.0f; // the file holds metres (an 800 mm plane at 0.8)
  core::saveCloudPcd(dir / "m.pcd", metres);
  devices::FileCamera camera(dir / "m.pcd");
  EXPECT_NEAR(camera.capture(1000ms).cloud.points_mm[15 * 40 + 20].z(),
              mm.points_mm[15 * 40 + 20].z(), 1e-3);
}

TEST(FileCamera, VanishedFileEndsWithAClearErrorAndReopenContinues) {
  test::TempDir dir;
  writeSequence(dir.path());
  devices::FileCamera camera(dir.path());
  camera.capture(1000ms);
  std::filesystem::remove(dir / "frame-1.pcd");
  try {
    camera.capture(1000ms);
    FAIL();
  } catch (const devices::DeviceError& e) {
    EXPECT_EQ(e.kind(), devices::DeviceErrorKind::StreamEnded);
    EXPECT_NE(std::string(e.what()).find("frame-1.pcd"), std::string::npos) << e.what();
  }
  devices::FileCamera reopened(dir.path());
  EXPECT_EQ(reopened.files().size(), 2u);
  reopened.capture(1000ms);
}

TEST(FileCamera, StreamCallsBackOnTheDeviceThreadAndReportsTheEnd) {
  test::TempDir dir;
  writeSequence(dir.path());
  devices::FileCamera camera(dir.path());
  std::mutex m;
  std::condition_variable cv;
  std::vector<std::uint64_t> indices;
  std::optional<devices::DeviceErrorKind> end;
  camera.startStream(
      [&](const devices::Frame& f) {
        std::lock_guard lock(m);
        indices.push_back(f.metadata.frame_index);
      },
      [&](const devices::DeviceError& e) {
        std::lock_guard lock(m);
        end = e.kind();
        cv.notify_all();
      },
      1000ms);
  {
    std::unique_lock lock(m);
    ASSERT_TRUE(cv.wait_for(lock, 10s, [&] { return end.has_value(); }));
  }
  camera.stopStream();
  EXPECT_EQ(indices, (std::vector<std::uint64_t>{0, 1, 2}));
  EXPECT_EQ(*end, devices::DeviceErrorKind::StreamEnded);
}

TEST(FileCamera, SecondStreamOrCaptureWhileStreamingIsBusy) {
  test::TempDir dir;
  writeSequence(dir.path());
  devices::FileCamera camera(dir.path(), /*loop=*/true); // never ends by itself
  std::atomic<int> frames{0};
  camera.startStream([&](const devices::Frame&) { ++frames; }, {}, 1000ms);
  EXPECT_EQ(kindOf([&] { camera.startStream({}, {}, 1000ms); }), devices::DeviceErrorKind::Busy);
  EXPECT_EQ(kindOf([&] { camera.capture(1000ms); }), devices::DeviceErrorKind::Busy);
  camera.stopStream();
  EXPECT_FALSE(camera.isStreaming());
  EXPECT_NO_THROW(camera.capture(1000ms)); // usable again after the stream
}

TEST(CameraRegistry, BadIdsSayWhatToDo) {
  for (const std::string id : {"nonsense", "webcam:0", "kinect:abc", "file:/no/such/folder"}) {
    try {
      devices::openCamera(id);
      ADD_FAILURE() << id;
    } catch (const devices::DeviceError& e) {
      EXPECT_EQ(e.kind(), devices::DeviceErrorKind::NotFound) << id;
      const std::string what = e.what();
      EXPECT_TRUE(what.find("kinect:") != std::string::npos ||
                  what.find("check the path") != std::string::npos)
          << what;
    }
  }
}

TEST(CameraRegistry, KinectIndexWithNothingPluggedInIsNotFound) {
  // No Kinect on test machines: the real libfreenect finds none.
  if (!devices::listKinectUsbDevices().empty())
    GTEST_SKIP() << "a real Kinect is attached; this test checks the message when none is";
  try {
    devices::openCamera("kinect:0");
    FAIL();
  } catch (const devices::DeviceError& e) {
    EXPECT_EQ(e.kind(), devices::DeviceErrorKind::NotFound);
    EXPECT_NE(std::string(e.what()).find("045e:02ae"), std::string::npos) << e.what();
  }
}

TEST(CaptureWriter, FramesAndSidecarsAreWrittenAtomicallyWithNumberedNames) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path() / "in");
  writeSequence(dir.path() / "in");
  devices::FileCamera camera(dir.path() / "in");
  const auto out = dir.path() / "out" / "scan.pcd";
  std::filesystem::create_directories(out.parent_path());
  const auto files = devices::captureToFiles(camera, out, 2, 1000ms);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].filename(), "scan-000.pcd");
  EXPECT_EQ(files[1].filename(), "scan-001.pcd");
  const auto meta = nlohmann::json::parse(core::readFile(out.parent_path() / "scan-001.json"));
  EXPECT_EQ(meta["format"], "scanpick-capture");
  EXPECT_EQ(meta["version"], 1);
  EXPECT_EQ(meta["units"], "mm");
  EXPECT_EQ(meta["sensor"], "file");
  EXPECT_EQ(meta["frame_index"], 1);
  EXPECT_EQ(meta["width"], 40);
  EXPECT_TRUE(meta["intrinsics"].is_null());
  const auto back = core::loadCloud(files[1], core::LengthUnit::Millimetres).cloud;
  EXPECT_EQ(back.height, 30u);

  // Asking for more frames than there are: the error says how many were saved, and the saved
  // ones are complete (no temporary or partial file).
  devices::FileCamera again(dir.path() / "in");
  try {
    devices::captureToFiles(again, dir.path() / "out" / "more.pcd", 5, 1000ms);
    FAIL();
  } catch (const devices::DeviceError& e) {
    EXPECT_EQ(e.kind(), devices::DeviceErrorKind::StreamEnded);
    EXPECT_NE(std::string(e.what()).find("3 of 5 frame(s) were saved"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(test::fileCount(dir.path() / "out"), 4u + 6u);
  EXPECT_EQ(devices::framePath("a/b.pcd", 0, 1), std::filesystem::path("a/b.pcd"));
}

TEST(UsbMonitor, NothingPluggedInIsAnEmptyListNotAnError) {
  std::vector<devices::KinectUsbDevice> list;
  ASSERT_NO_THROW(list = devices::listKinectUsbDevices());
  for (const auto& d : list) // on a machine with a Kinect, only Kinect functions are listed
    EXPECT_TRUE(d.role == devices::KinectUsbRole::Camera ||
                d.role == devices::KinectUsbRole::Motor || d.role == devices::KinectUsbRole::Audio);
  std::atomic<int> events{0};
  {
    devices::UsbMonitor monitor([&](const devices::UsbEvent&) { ++events; }, 50);
    std::this_thread::sleep_for(200ms);
  }                            // stops and joins
  EXPECT_EQ(events.load(), 0); // nothing was plugged in meanwhile
}

TEST(UsbMonitor, DiffReportsArrivalsAndRemovals) {
  const devices::KinectUsbDevice cam{devices::KinectUsbRole::Camera, 1, 5, "1-2"};
  const devices::KinectUsbDevice motor{devices::KinectUsbRole::Motor, 1, 4, "1-2"};
  const devices::KinectUsbDevice cam_replugged{devices::KinectUsbRole::Camera, 1, 9, "1-2"};
  const auto events = devices::diffUsbDevices({motor, cam}, {motor, cam_replugged});
  ASSERT_EQ(events.size(), 2u);
  EXPECT_FALSE(events[0].arrived);
  EXPECT_EQ(events[0].device, cam);
  EXPECT_TRUE(events[1].arrived);
  EXPECT_EQ(events[1].device, cam_replugged);
  EXPECT_TRUE(devices::diffUsbDevices({cam}, {cam}).empty());
}
