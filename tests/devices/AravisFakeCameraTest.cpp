// PhoXiGigECamera against Aravis's real GigE Vision fake camera on loopback: the full path
// (GVCP control, software trigger, GVSP streaming, decoding) runs; only the sensor is simulated.
// The fake streams a synthetic bin scene as Coord3D_ABC32f through our fill callback.
#include "core/sim/PartCatalog.h"
#include "core/sim/Renderer.h"
#include "devices/aravis/PhoXiGigECamera.h"
#include "tests/devices/SyntheticScene.h"
#include "tests/support/TempDir.h"

#include <arv.h>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <gtest/gtest.h>
#include <mutex>
#include <sys/file.h>
#include <unistd.h>

using namespace scanpick;
using namespace std::chrono_literals;

namespace {

constexpr std::uint32_t kWidth = 320, kHeight = 240;
constexpr std::uint32_t kCoord3dAbc32f = 0x026000C0;

struct SceneSource {
  core::PointCloud cloud;
  std::atomic<int> filled{0};
};

/// Fill callback (fake camera thread): the scene as XYZ float triplets; (0,0,0) where invalid,
/// as PhoXi marks missing points.
void fillScene(ArvBuffer* buffer, void* user, guint32, guint32, ArvPixelFormat format) {
  auto* scene = static_cast<SceneSource*>(user);
  // Inside the fill callback Aravis has not set the received size yet (get_data reports 0), but
  // the buffer is allocated for the payload of the current width, height and pixel format.
  size_t size = 0;
  auto* data = static_cast<float*>(const_cast<void*>(arv_buffer_get_data(buffer, &size)));
  const auto w = static_cast<std::uint32_t>(arv_buffer_get_image_width(buffer));
  const auto h = static_cast<std::uint32_t>(arv_buffer_get_image_height(buffer));
  if (format != kCoord3dAbc32f || w != scene->cloud.width || h != scene->cloud.height || !data)
    return;
  for (std::size_t i = 0; i < scene->cloud.size(); ++i) {
    const Eigen::Vector3f& p = scene->cloud.points_mm[i];
    const Eigen::Vector3f out = core::isValid(p) ? p : Eigen::Vector3f::Zero();
    std::memcpy(data + 3 * i, out.data(), 12);
  }
  ++scene->filled;
}

/// Aravis's default fake GenICam XML plus the Coord3D_ABC32f pixel format (an enum entry only).
std::filesystem::path writeGenicamXml(const std::filesystem::path& dir) {
  ArvFakeCamera* probe = arv_fake_camera_new("xml-source");
  size_t size = 0;
  const char* text = arv_fake_camera_get_genicam_xml(probe, &size);
  std::string xml(text, size);
  g_object_unref(probe);
  const std::string anchor = "<pValue>PixelFormatRegister</pValue>";
  const auto at = xml.find(anchor);
  EXPECT_NE(at, std::string::npos);
  xml.insert(at, "<EnumEntry Name=\"Coord3D_ABC32f\" "
                 "NameSpace=\"Standard\"><Value>39846080</Value></EnumEntry>\n\t\t");
  const auto path = dir / "phoxi-fake.xml";
  std::ofstream(path, std::ios::binary) << xml;
  return path;
}

/// The fake binds the GVCP port on 127.0.0.1 (it only accepts an interface's own address), so
/// tests of this file that ctest runs in parallel take turns through a file lock.
class LoopbackLock {
public:
  LoopbackLock() {
    m_fd = ::open((std::filesystem::temp_directory_path() / "scanpick-aravis-fake.lock").c_str(),
                  O_CREAT | O_RDWR, 0666);
    if (m_fd >= 0)
      ::flock(m_fd, LOCK_EX);
  }
  ~LoopbackLock() {
    if (m_fd >= 0)
      ::close(m_fd); // releases the lock
  }
  LoopbackLock(const LoopbackLock&) = delete;
  LoopbackLock& operator=(const LoopbackLock&) = delete;

private:
  int m_fd = -1;
};

/// A fake GigE Vision scanner on the loopback interface.
class FakeScanner {
public:
  FakeScanner(const std::string& address, const std::filesystem::path& xml, SceneSource& scene) {
    m_gv = arv_gv_fake_camera_new_full(address.c_str(), "PHX-FAKE-1", xml.string().c_str());
    if (!m_gv || !arv_gv_fake_camera_is_running(m_gv))
      return;
    ArvFakeCamera* fake = arv_gv_fake_camera_get_fake_camera(m_gv);
    arv_fake_camera_write_register(fake, ARV_FAKE_CAMERA_REGISTER_WIDTH, scene.cloud.width);
    arv_fake_camera_write_register(fake, ARV_FAKE_CAMERA_REGISTER_HEIGHT, scene.cloud.height);
    arv_fake_camera_set_fill_pattern(fake, &fillScene, &scene);
  }
  ~FakeScanner() { destroy(); }
  void destroy() {
    if (m_gv)
      g_object_unref(m_gv);
    m_gv = nullptr;
  }
  [[nodiscard]] bool running() const { return m_gv && arv_gv_fake_camera_is_running(m_gv); }

private:
  ArvGvFakeCamera* m_gv = nullptr;
};

/// Exact comparison: the decoder must return the floats that were sent, NaN where (0,0,0) was sent.
void expectSameCloud(const core::PointCloud& got, const core::PointCloud& sent) {
  ASSERT_EQ(got.width, sent.width);
  ASSERT_EQ(got.height, sent.height);
  std::size_t mismatches = 0, invalid = 0;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    if (!core::isValid(sent.points_mm[i])) {
      ++invalid;
      mismatches += core::isValid(got.points_mm[i]) ? 1 : 0;
    } else {
      mismatches += got.points_mm[i] == sent.points_mm[i] ? 0 : 1;
    }
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(invalid, 0u);
  EXPECT_EQ(got.validCount(), sent.validCount());
}

} // namespace

TEST(AravisFakeCamera, SoftwareTriggeredCaptureReturnsTheSentScene) {
  LoopbackLock loopback;
  test::TempDir dir;
  SceneSource scene{test::syntheticBinScene(kWidth, kHeight)};
  FakeScanner fake("127.0.0.1", writeGenicamXml(dir.path()), scene);
  ASSERT_TRUE(fake.running()) << "the fake GigE Vision camera could not bind 127.0.0.11";

  devices::PhoXiGigECamera camera("127.0.0.1");
  EXPECT_EQ(camera.info().serial, "PHX-FAKE-1");
  for (int shot = 0; shot < 2; ++shot) {
    const devices::Frame frame = camera.capture(5000ms);
    expectSameCloud(frame.cloud, scene.cloud);
    EXPECT_EQ(frame.metadata.frame_index, static_cast<std::uint64_t>(shot));
    EXPECT_EQ(frame.metadata.serial, "PHX-FAKE-1");
  }
  EXPECT_GE(scene.filled.load(), 2);
}

TEST(AravisFakeCamera, VirtualScannerBinSceneArrivesUnchanged) {
  // A bin of pump connectors dropped with physics and rendered by core/sim's virtual PhoXi M
  // (typical noise, shadows, dropouts), at a third of the resolution to keep the test quick.
  core::SensorModel sensor = core::sensorPreset("phoxi-m-1032");
  sensor.width /= 3;
  sensor.height /= 3;
  sensor.fx /= 3;
  sensor.fy /= 3;
  sensor.cx = (sensor.width - 1) / 2.0;
  sensor.cy = (sensor.height - 1) / 2.0;
  core::SceneSpec spec;
  spec.layout = core::LayoutKind::Bin;
  spec.parts = {core::builtInPart("pump-connector")};
  spec.count = 3;
  spec.seed = 7;
  const core::Scene bin = core::buildScene(spec, sensor);
  SceneSource scene{core::renderScene(bin, sensor, core::SensorNoise::typical(sensor), 7).cloud};
  ASSERT_GT(scene.cloud.validCount(), scene.cloud.size() / 2);

  LoopbackLock loopback;
  test::TempDir dir;
  FakeScanner fake("127.0.0.1", writeGenicamXml(dir.path()), scene);
  ASSERT_TRUE(fake.running())
      << "the fake GigE Vision camera could not bind 127.0.0.1 (UDP port 3956)";
  devices::PhoXiGigECamera camera("127.0.0.1");
  const devices::Frame frame = camera.capture(5000ms);
  expectSameCloud(frame.cloud, scene.cloud);
}

TEST(AravisFakeCamera, StreamDeliversFramesOnTheDeviceThread) {
  LoopbackLock loopback;
  test::TempDir dir;
  SceneSource scene{test::syntheticBinScene(kWidth, kHeight)};
  FakeScanner fake("127.0.0.1", writeGenicamXml(dir.path()), scene);
  ASSERT_TRUE(fake.running());
  devices::PhoXiGigECamera camera("127.0.0.1");

  std::mutex mutex;
  std::condition_variable cv;
  int frames = 0;
  bool all_equal = true;
  const auto caller = std::this_thread::get_id();
  bool on_other_thread = true;
  camera.startStream(
      [&](const devices::Frame& f) {
        std::lock_guard lock(mutex);
        all_equal = all_equal && f.cloud.validCount() == scene.cloud.validCount() &&
                    f.cloud.points_mm[kWidth * kHeight / 2 + kWidth / 2] ==
                        scene.cloud.points_mm[kWidth * kHeight / 2 + kWidth / 2];
        on_other_thread = on_other_thread && std::this_thread::get_id() != caller;
        ++frames;
        cv.notify_all();
      },
      [](const devices::DeviceError& e) { ADD_FAILURE() << e.what(); }, 5000ms);
  {
    std::unique_lock lock(mutex);
    ASSERT_TRUE(cv.wait_for(lock, 20s, [&] { return frames >= 3; }));
  }
  camera.stopStream();
  EXPECT_TRUE(all_equal);
  EXPECT_TRUE(on_other_thread);
  EXPECT_FALSE(camera.isStreaming());
}

TEST(AravisFakeCamera, VanishedScannerEndsWithinTimeoutAndReopenWorks) {
  LoopbackLock loopback;
  test::TempDir dir;
  const auto xml = writeGenicamXml(dir.path());
  SceneSource scene{test::syntheticBinScene(kWidth, kHeight)};
  auto fake = std::make_unique<FakeScanner>("127.0.0.1", xml, scene);
  ASSERT_TRUE(fake->running());
  auto camera = std::make_unique<devices::PhoXiGigECamera>("127.0.0.1");
  camera->capture(5000ms);

  fake->destroy(); // power cut
  const auto start = std::chrono::steady_clock::now();
  try {
    camera->capture(1500ms);
    FAIL() << "capture succeeded without a scanner";
  } catch (const devices::DeviceError& e) {
    EXPECT_TRUE(e.kind() == devices::DeviceErrorKind::StreamEnded ||
                e.kind() == devices::DeviceErrorKind::Timeout)
        << devices::toString(e.kind());
    EXPECT_NE(std::string(e.what()).find("reopen"), std::string::npos) << e.what();
  }
  // Within the configured timeout (plus scheduling slack), although Aravis itself would retry
  // the trigger command for seconds.
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_LT(elapsed, 1500ms + 500ms);
  const auto close_start = std::chrono::steady_clock::now();
  camera.reset();
  std::printf("vanished scanner: error after %lld ms (timeout 1500 ms), close took %lld ms\n",
              static_cast<long long>(
                  std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count()),
              static_cast<long long>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                         std::chrono::steady_clock::now() - close_start)
                                         .count()));

  SceneSource scene2{test::syntheticBinScene(kWidth, kHeight, 400.0, 25.0f)};
  FakeScanner again("127.0.0.1", xml, scene2);
  ASSERT_TRUE(again.running());
  devices::PhoXiGigECamera reopened("127.0.0.1");
  expectSameCloud(reopened.capture(5000ms).cloud, scene2.cloud);
}

TEST(AravisFakeCamera, UnknownScannerSaysWhatToDo) {
  try {
    devices::PhoXiGigECamera camera("PHX-DOES-NOT-EXIST");
    FAIL();
  } catch (const devices::DeviceError& e) {
    EXPECT_EQ(e.kind(), devices::DeviceErrorKind::NotFound);
    EXPECT_NE(std::string(e.what()).find("scanpick-cli devices"), std::string::npos) << e.what();
  }
}
