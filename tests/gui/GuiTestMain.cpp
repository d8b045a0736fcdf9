// main() of the GUI tests: a QApplication with VTK's surface format around GoogleTest. Listing the
// tests (ctest discovery at build time) needs no display, so no QApplication is made for it.
#include "ui/viewport/QtVtkViewport.h"

#include <QApplication>
#include <QSettings>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>

int main(int argc, char** argv) {
  bool listing = false;
  for (int i = 1; i < argc; ++i)
    listing = listing || std::strncmp(argv[i], "--gtest_list_tests", 18) == 0;
  testing::InitGoogleTest(&argc, argv);
  std::unique_ptr<QApplication> app;
  std::unique_ptr<QTemporaryDir> settings_dir;
  if (!listing) {
    QSurfaceFormat::setDefaultFormat(scanpick::ui::QtVtkViewport::defaultFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    app = std::make_unique<QApplication>(argc, argv);
    QApplication::setOrganizationName("scanpick-tests");
    QApplication::setApplicationName("scanpick-gui-tests");
    // QSettings and caches go to a test location, never the user's.
    QStandardPaths::setTestModeEnabled(true);
    // Each test process has settings of its own, empty at the start, so no test sees what another
    // left behind (last preset, device id, layout) or what one running beside it writes (ctest -j).
    settings_dir = std::make_unique<QTemporaryDir>();
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, settings_dir->path());
    QSettings().clear();
  }
  return RUN_ALL_TESTS();
}
