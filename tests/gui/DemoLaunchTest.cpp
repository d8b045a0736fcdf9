// The README's main job with a display: `scanpick --scan demo-bin.pcd --model support.spmodel
// --model support-table.spmodel --recognize` (what ./cmake/setup.sh demo runs after
// `scanpick-cli demo`) opens the application with the part's two views, recognizes the demo bin
// and shows the overlay. Run here as a separate process with --screenshot, on scenes and models
// made at test time like `scanpick-cli demo` makes them.
#include "core/cloud/CloudIo.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "core/pipeline/Recognizer.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/gui/SyntheticScenes.h"
#include "ui/viewport/Presenters.h"

#include <QImage>
#include <QProcess>
#include <gtest/gtest.h>

using namespace scanpick;
namespace fs = std::filesystem;

TEST(DemoLaunch, GuiOpensOnTheDemoAndShowsTheRecognizedBin) {
  const QString gui = QStringLiteral(SCANPICK_BINARY_DIR "/bin/scanpick");
  if (!QFile::exists(gui))
    GTEST_SKIP() << gui.toStdString() << " is not built (build the scanpick target first)";
  const test::DemoScenes scenes;
  const core::RecognitionParams params =
      core::loadPreset(test::phoxiBinPreset().toStdString()).params;
  // The demo's two views: the support on its legs, and lying on the table.
  std::vector<std::shared_ptr<const core::TaughtModel>> views;
  QStringList model_args;
  for (const auto& path : scenes.teachDemoViews(params)) {
    views.push_back(std::make_shared<const core::TaughtModel>(core::loadModel(path)));
    model_args << QStringLiteral("--model") << QString::fromStdString(path.string());
  }
  // What the window must find: the core's answer for the same inputs.
  core::Recognizer recognizer;
  const std::size_t expected =
      core::recognizeViews(recognizer, core::joinViews(views),
                           core::loadCloud(scenes.bin_scan, core::LengthUnit::Millimetres).cloud,
                           core::sensorPreset("phoxi-m-1032"), params)
          .detections.size();

  const QString shot = QString::fromStdString((scenes.dir / "gui-demo.png").string());
  QProcess process;
  process.setProcessChannelMode(QProcess::MergedChannels);
  // A private settings folder, so a restored layout or preset cannot change the run.
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert(QStringLiteral("XDG_CONFIG_HOME"),
             QString::fromStdString((scenes.dir / "config").string()));
  process.setProcessEnvironment(env);
  process.start(
      gui, QStringList{QStringLiteral("--scan"), QString::fromStdString(scenes.bin_scan.string())}
               << model_args
               << QStringList{QStringLiteral("--recognize"), QStringLiteral("--screenshot"), shot,
                              QStringLiteral("--quit-after-screenshot")});
  ASSERT_TRUE(process.waitForFinished(50000)) << "scanpick did not finish";
  const QString output = QString::fromUtf8(process.readAll());
  ASSERT_EQ(process.exitCode(), 0) << output.toStdString();
  EXPECT_TRUE(output.contains(QStringLiteral("recognized %1 instance(s)").arg(expected)))
      << output.toStdString();
  EXPECT_TRUE(output.contains(QStringLiteral("view 2 (")) &&
              output.contains("support-table.spmodel"))
      << "the second view was not opened: " << output.toStdString();
  const QImage image(shot);
  ASSERT_FALSE(image.isNull()) << "no screenshot written";
  image.save(test::screenshotDir() + "/demo-launch.png");
  EXPECT_GT(test::countGrey(image), 1000) << "the scene (greys by depth) is missing";
  if (expected > 0) {
    EXPECT_GT(test::countColour(image, ui::detectionColour(0), 30), 20)
        << "the first detection's overlay colour is missing";
  }
}
