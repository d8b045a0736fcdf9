// Tools → Hand-eye calibration in a real window, on the simulated robot cell of the CLI's test
// (tests/integration/CliCalibrateTest.cpp): 8 PhoXi scans of the target carried by the robot
// (eye-to-hand) and a poses file with the flange poses in metres. The dialog lists the poses,
// calibrates in the background to within 0.2 mm / 0.05° of the cell's truth, fills every row with
// its residual (a wrong robot pose rejected with the reason), saves a file that
// core::calib::loadCalibration reads back and that holds what `scanpick-cli calibrate` writes for
// the same input. Bad input (a missing scan, a poses file that is not JSON, too few poses,
// rotations about one axis) shows the reason, writes nothing and leaves the dialog and the window
// usable; a running calibration can be cancelled; the texts follow the language.
#include "ui/panels/CalibrationWizard.h"

#include "core/calib/CalibJson.h"
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"
#include "tests/unit/calib/CalibScenes.h"
#include "ui/Language.h"
#include "ui/MainWindow.h"

#include <QAction>
#include <QApplication>
#include <QFileDialog>
#include <QHeaderView>
#include <QMenuBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTest>
#include <QTimer>
#include <gtest/gtest.h>
#include <iostream>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using namespace scanpick;
using json = nlohmann::json;
using ui::CalibrationWizard;
using ui::MainWindow;

namespace {

constexpr int kPoses = 8;
constexpr int kCalibrationTimeoutMs = 180000;

/// A flange pose in the poses file, translations in metres (as a UR robot reports them).
json poseInMetres(const Eigen::Isometry3d& T_base_flange) {
  json pose = core::calib::poseToJson(T_base_flange);
  pose.erase("matrix");
  for (const char* k : {"x", "y", "z"})
    pose[k] = pose[k].get<double>() / 1000;
  return pose;
}

QString qpath(const fs::path& p) {
  return QString::fromStdString(p.string());
}

class CalibrationWizardTest : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    s_dir = std::make_unique<test::TempDir>();
    s_cell = test::eyeToHandCell(kPoses, 21);
    const auto mesh = test::targetMesh(core::calib::defaultTarget());
    json poses = json::array();
    for (int i = 0; i < kPoses; ++i) {
      const std::string scan = "scan-" + std::to_string(i + 1) + ".pcd";
      core::saveCloudPcd(*s_dir / scan, core::dropInvalid(test::scanOf(s_cell, i, mesh)));
      poses.push_back(
          {{"scan", scan}, {"T_base_flange", poseInMetres(s_cell.T_base_flange[std::size_t(i)])}});
    }
    core::writeFileAtomic(*s_dir / "poses.json", poses.dump(2));
    // Pose 5 with the flange 2 mm off in x: a wrong robot pose.
    json wrong = poses;
    wrong[4]["T_base_flange"]["x"] = wrong[4]["T_base_flange"]["x"].get<double>() + 0.002;
    core::writeFileAtomic(*s_dir / "wrong.json", wrong.dump(2));
    poses[2]["scan"] = "missing-3.pcd";
    core::writeFileAtomic(*s_dir / "missing.json", poses.dump(2));
    core::writeFileAtomic(*s_dir / "broken.json", "[{\"scan\": ");
    // Six poses that all turn about the base's z axis: the calibration is undetermined.
    json one_axis = json::array();
    for (int i = 0; i < 6; ++i)
      one_axis.push_back(
          {{"scan", "none.pcd"},
           {"T_base_flange", poseInMetres(test::pose({400.0 + 20 * i, -50.0 * i, 500},
                                                     test::rotation(15.0 * i, {0, 0, 1})))}});
    core::writeFileAtomic(*s_dir / "one-axis.json", one_axis.dump(2));
    json two = json::array({one_axis[0], one_axis[1]});
    core::writeFileAtomic(*s_dir / "two.json", two.dump(2));
  }
  static void TearDownTestSuite() { s_dir.reset(); }

  /// Opens the dialog through Tools → Hand-eye calibration… in the shown window.
  CalibrationWizard* openWizard() {
    window.show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(&window));
    auto* action = window.findChild<QAction*>(QStringLiteral("handEyeCalibrationAction"));
    EXPECT_NE(action, nullptr);
    if (!action)
      return nullptr;
    action->trigger();
    auto* wizard = window.findChild<CalibrationWizard*>(QStringLiteral("calibrationWizard"));
    EXPECT_NE(wizard, nullptr);
    if (wizard) {
      EXPECT_TRUE(QTest::qWaitForWindowExposed(wizard));
    }
    return wizard;
  }
  static QPushButton* button(CalibrationWizard* wizard, const char* name) {
    return wizard->findChild<QPushButton*>(QString::fromLatin1(name));
  }
  /// Clicks Calibrate and waits for the end; returns whether it succeeded.
  static bool calibrateAndWait(CalibrationWizard* wizard) {
    QSignalSpy finished(wizard, &CalibrationWizard::calibrationFinished);
    QTest::mouseClick(button(wizard, "calibrateButton"), Qt::LeftButton);
    EXPECT_EQ(wizard->state(), CalibrationWizard::State::Running);
    EXPECT_TRUE(finished.wait(kCalibrationTimeoutMs)) << "the calibration did not end";
    return !finished.isEmpty() && finished.first().first().toBool();
  }
  static QString cell(CalibrationWizard* wizard, int row, int column) {
    const QTableWidgetItem* item = wizard->table()->item(row, column);
    return item ? item->text() : QString();
  }

  static inline std::unique_ptr<test::TempDir> s_dir;
  static inline test::SimulatedCell s_cell;
  test::TempDir m_out;
  MainWindow window;
};

} // namespace

TEST_F(CalibrationWizardTest, CalibratesAfterAMissingScanAndSavesWhatTheCoreReadsBack) {
  CalibrationWizard* wizard = openWizard();
  ASSERT_NE(wizard, nullptr);
  wizard->setUnits(QStringLiteral("mm"), QStringLiteral("m"));

  // Scan 3 is missing: scans 1 and 2 are searched, then the run stops naming scan 3.
  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "missing.json")))
      << wizard->messageText().toStdString();
  ASSERT_EQ(wizard->table()->rowCount(), kPoses);
  EXPECT_FALSE(calibrateAndWait(wizard));
  EXPECT_EQ(wizard->state(), CalibrationWizard::State::Failed);
  EXPECT_TRUE(wizard->messageText().contains(
      QStringLiteral("scan 3 (%1): ").arg(qpath(*s_dir / "missing-3.pcd"))))
      << wizard->messageText().toStdString();
  EXPECT_EQ(cell(wizard, 2, CalibrationWizard::StatusCol), QStringLiteral("failed"));
  EXPECT_EQ(cell(wizard, 0, CalibrationWizard::SpheresCol), QStringLiteral("4 of 4"));
  EXPECT_EQ(wizard->result(), nullptr);
  EXPECT_FALSE(button(wizard, "saveCalibrationButton")->isEnabled());
  EXPECT_FALSE(wizard->saveTo(qpath(m_out / "refused.json")));
  EXPECT_FALSE(fs::exists(m_out / "refused.json"));

  // The same dialog then calibrates the complete set.
  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "poses.json")))
      << wizard->messageText().toStdString();
  ASSERT_TRUE(calibrateAndWait(wizard)) << wizard->messageText().toStdString();
  ASSERT_EQ(wizard->state(), CalibrationWizard::State::Done);
  const core::calib::HandEyeResult* result = wizard->result();
  ASSERT_NE(result, nullptr);
  const double camera_mm = test::distanceBetween_mm(result->T_camera, s_cell.X);
  const double camera_deg = test::angleBetween_deg(result->T_camera, s_cell.X);
  const double target_mm = test::distanceBetween_mm(result->T_target, s_cell.Y);
  const double target_deg = test::angleBetween_deg(result->T_target, s_cell.Y);
  std::cout << "GUI calibration against the truth: T_base_camera " << camera_mm << " mm, "
            << camera_deg << " deg; T_flange_target " << target_mm << " mm, " << target_deg
            << " deg; residual RMS " << result->rms_mm << " mm\n";
  EXPECT_LT(camera_mm, 0.2);
  EXPECT_LT(camera_deg, 0.05);
  EXPECT_LT(target_mm, 0.2);
  EXPECT_LT(target_deg, 0.05);
  EXPECT_EQ(result->poses_used, kPoses);

  // One row per pose with its spheres, fit and residual.
  ASSERT_EQ(wizard->table()->rowCount(), kPoses);
  for (int row = 0; row < kPoses; ++row) {
    SCOPED_TRACE(row);
    EXPECT_EQ(cell(wizard, row, CalibrationWizard::ScanCol),
              QStringLiteral("scan-%1.pcd").arg(row + 1));
    EXPECT_EQ(cell(wizard, row, CalibrationWizard::SpheresCol), QStringLiteral("4 of 4"));
    EXPECT_EQ(cell(wizard, row, CalibrationWizard::StatusCol), QStringLiteral("used"));
    bool ok = false;
    const double rms = cell(wizard, row, CalibrationWizard::RmsCol).toDouble(&ok);
    EXPECT_TRUE(ok);
    EXPECT_NEAR(rms, result->residuals[std::size_t(row)].rms_mm, 0.0005);
    EXPECT_LT(rms, 0.3);
    EXPECT_FALSE(cell(wizard, row, CalibrationWizard::RotCol).isEmpty());
  }
  EXPECT_TRUE(wizard->resultText().contains(QStringLiteral("from 8 of 8 poses")))
      << wizard->resultText().toStdString();
  EXPECT_TRUE(wizard->resultText().contains(QStringLiteral("T_base_camera: position ")));
  QTest::qWait(50); // the layout follows the new texts
  wizard->grab().save(test::screenshotDir() + QStringLiteral("/calibration-wizard.png"));

  // Save through the button and the save dialog: ".json" is added to the name typed.
  ASSERT_TRUE(button(wizard, "saveCalibrationButton")->isEnabled());
  const QString typed = qpath(m_out / "cell-calibration");
  QTimer::singleShot(0, wizard, [typed] {
    auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
    ASSERT_NE(dialog, nullptr) << "no save dialog";
    dialog->selectFile(typed);
    QMetaObject::invokeMethod(dialog, "accept");
  });
  QTest::mouseClick(button(wizard, "saveCalibrationButton"), Qt::LeftButton);
  const fs::path saved = m_out / "cell-calibration.json";
  ASSERT_TRUE(fs::exists(saved)) << wizard->messageText().toStdString();
  EXPECT_TRUE(wizard->messageText().startsWith(QStringLiteral("Calibration saved to ")));
  const core::calib::HandEyeResult read = core::calib::loadCalibration(saved);
  EXPECT_EQ(read.mode, core::calib::HandEyeMode::EyeToHand);
  EXPECT_LT(test::distanceBetween_mm(read.T_camera, result->T_camera), 1e-6);
  EXPECT_LT(test::angleBetween_deg(read.T_camera, result->T_camera), 1e-6);
  EXPECT_LT(test::distanceBetween_mm(read.T_target, result->T_target), 1e-6);
  EXPECT_TRUE(window.isVisible());
}

// The dialog and `scanpick-cli calibrate` run the same core steps: same input, same file.
TEST_F(CalibrationWizardTest, SavesWhatTheCliWrites) {
  if (!fs::exists(test::kCli))
    GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  const fs::path cli_out = m_out / "cli.json";
  ASSERT_EQ(test::exitCode(test::runCli({"calibrate", "--mode", "eye-to-hand", "--poses",
                                         test::quoted(*s_dir / "poses.json"), "--pose-units", "m",
                                         "--out", test::quoted(cli_out)})),
            0);
  CalibrationWizard* wizard = openWizard();
  ASSERT_NE(wizard, nullptr);
  wizard->setUnits(QStringLiteral("mm"), QStringLiteral("m"));
  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "poses.json")));
  ASSERT_TRUE(calibrateAndWait(wizard)) << wizard->messageText().toStdString();
  ASSERT_TRUE(wizard->saveTo(qpath(m_out / "gui.json")));
  const json gui = json::parse(test::readText(m_out / "gui.json"));
  const json cli = json::parse(test::readText(cli_out));
  for (const char* key : {"mode", "T_base_camera", "T_flange_target", "poses_used", "residuals"})
    EXPECT_EQ(gui.at(key), cli.at(key)) << key;
}

TEST_F(CalibrationWizardTest, AWrongRobotPoseIsRejectedWithItsReason) {
  CalibrationWizard* wizard = openWizard();
  ASSERT_NE(wizard, nullptr);
  wizard->setUnits(QStringLiteral("mm"), QStringLiteral("m"));
  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "wrong.json")));
  ASSERT_TRUE(calibrateAndWait(wizard)) << wizard->messageText().toStdString();
  const core::calib::HandEyeResult* result = wizard->result();
  ASSERT_NE(result, nullptr);
  EXPECT_EQ(result->poses_used, kPoses - 1);
  for (int row = 0; row < kPoses; ++row) {
    const QString status = cell(wizard, row, CalibrationWizard::StatusCol);
    if (row == 4) {
      EXPECT_TRUE(status.startsWith(QStringLiteral("rejected: ")));
      EXPECT_TRUE(
          status.contains(QStringLiteral("the robot pose or the scan of this pose is wrong")))
          << status.toStdString();
    } else {
      EXPECT_EQ(status, QStringLiteral("used")) << row;
    }
  }
  EXPECT_TRUE(wizard->resultText().contains(QStringLiteral("from 7 of 8 poses")))
      << wizard->resultText().toStdString();
  EXPECT_TRUE(wizard->resultText().contains(QStringLiteral("1 pose(s) rejected")));
  EXPECT_LT(test::distanceBetween_mm(result->T_camera, s_cell.X), 0.2);
  EXPECT_LT(test::angleBetween_deg(result->T_camera, s_cell.X), 0.05);
}

TEST_F(CalibrationWizardTest, BadPoseSetsShowTheReasonAndWriteNothing) {
  CalibrationWizard* wizard = openWizard();
  ASSERT_NE(wizard, nullptr);
  wizard->setUnits(QStringLiteral("mm"), QStringLiteral("m"));
  QPushButton* calibrate = button(wizard, "calibrateButton");

  EXPECT_FALSE(wizard->loadPosesFile(qpath(*s_dir / "broken.json")));
  EXPECT_TRUE(wizard->messageText().startsWith(QStringLiteral("The poses file could not be read:")))
      << wizard->messageText().toStdString();
  EXPECT_TRUE(wizard->messageText().contains(QStringLiteral("is not valid JSON")))
      << wizard->messageText().toStdString();
  EXPECT_EQ(wizard->table()->rowCount(), 0);
  EXPECT_FALSE(calibrate->isEnabled());

  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "one-axis.json")));
  EXPECT_EQ(wizard->table()->rowCount(), 6);
  EXPECT_FALSE(calibrateAndWait(wizard));
  EXPECT_TRUE(wizard->messageText().contains(
      QStringLiteral("degenerate motion: all rotations between the robot poses are about "
                     "(nearly) one axis")))
      << wizard->messageText().toStdString();

  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "two.json")));
  EXPECT_FALSE(calibrateAndWait(wizard));
  EXPECT_TRUE(wizard->messageText().contains(QStringLiteral("too few poses: 2 given")))
      << wizard->messageText().toStdString();
  EXPECT_FALSE(button(wizard, "saveCalibrationButton")->isEnabled());
  EXPECT_FALSE(wizard->saveTo(qpath(m_out / "calibration.json")));
  EXPECT_EQ(test::fileCount(m_out.path()), 0u) << "nothing is written";

  // A running calibration stops on Cancel; no late result replaces the message.
  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "poses.json")));
  QSignalSpy finished(wizard, &CalibrationWizard::calibrationFinished);
  QTest::mouseClick(calibrate, Qt::LeftButton);
  ASSERT_EQ(wizard->state(), CalibrationWizard::State::Running);
  QTest::mouseClick(button(wizard, "cancelCalibrationButton"), Qt::LeftButton);
  EXPECT_EQ(wizard->state(), CalibrationWizard::State::Ready);
  EXPECT_EQ(wizard->messageText(), QStringLiteral("Calibration cancelled."));
  QTest::qWait(1500);
  EXPECT_EQ(finished.size(), 1);
  EXPECT_EQ(wizard->messageText(), QStringLiteral("Calibration cancelled."));
  EXPECT_EQ(wizard->result(), nullptr);
  EXPECT_TRUE(calibrate->isEnabled());

  // Closing the dialog leaves the window running; the menu opens a new one.
  QTest::mouseClick(button(wizard, "closeCalibrationButton"), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return !window.findChild<CalibrationWizard*>(QStringLiteral("calibrationWizard")); },
      10000))
      << "the closed dialog is deleted";
  EXPECT_TRUE(window.isVisible());
  CalibrationWizard* again = openWizard();
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again->state(), CalibrationWizard::State::NoPoses);
}

TEST_F(CalibrationWizardTest, TextsFollowTheLanguage) {
  CalibrationWizard* wizard = openWizard();
  ASSERT_NE(wizard, nullptr);
  ASSERT_TRUE(wizard->loadPosesFile(qpath(*s_dir / "poses.json")));
  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("it")));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return wizard->windowTitle() == QStringLiteral("Calibrazione mano-occhio"); }, 5000))
      << wizard->windowTitle().toStdString();
  EXPECT_EQ(button(wizard, "calibrateButton")->text(), QStringLiteral("&Calibra"));
  EXPECT_EQ(wizard->table()->horizontalHeaderItem(CalibrationWizard::ScanCol)->text(),
            QStringLiteral("Scansione"));
  EXPECT_EQ(wizard->messageText(), QStringLiteral("8 pose caricate: premere Calibra."));
  EXPECT_EQ(window.findChild<QAction*>(QStringLiteral("handEyeCalibrationAction"))->text(),
            QStringLiteral("Calibrazione &mano-occhio…"));
  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("en")));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return wizard->windowTitle() == QStringLiteral("Hand-eye calibration"); }, 5000));
  EXPECT_EQ(wizard->messageText(), QStringLiteral("8 pose(s) loaded: press Calibrate."));
}
