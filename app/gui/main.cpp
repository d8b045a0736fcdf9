// scanpick: the desktop application. Options let scripts and the docs drive it:
//   scanpick [--scan S] [--model M ...] [--preset P] [--recognize] [--screenshot out.png]
//            [--quit-after-screenshot] [files...]
// `./cmake/setup.sh demo` opens the demo this way:
//   scanpick --scan demo-output/demo-bin.pcd --model demo-output/support.spmodel
//            --model demo-output/support-table.spmodel --recognize
#include "core/cloud/CloudIo.h"
#include "core/common/Log.h"
#include "core/common/Memory.h"
#include "ui/Language.h"
#include "ui/MainWindow.h"
#include "ui/Settings.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QLocale>
#include <QSettings>
#include <QTimer>
#include <cstdio>

using scanpick::ui::MainWindow;

int main(int argc, char** argv) {
  scanpick::core::keepFreedMemoryForReuse(); // live recognition: scene after scene
  // VTK needs an OpenGL 3.2 core context; the default format must be set before QApplication.
  QSurfaceFormat::setDefaultFormat(scanpick::ui::QtVtkViewport::defaultFormat());
  QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("scanpick"));
  QApplication::setApplicationName(QStringLiteral("scanpick"));

  // The language can also be switched later from View → Language (ui/Language.h).
  scanpick::ui::applyLanguage(
      QSettings().value(scanpick::ui::settings::kLanguage, QStringLiteral("en")).toString());

  QCommandLineParser parser;
  parser.setApplicationDescription(
      QApplication::translate("main", "3D object recognition for bin picking, taught from a scan"));
  parser.addHelpOption();
  const QCommandLineOption scene({"s", "scan", "scene"}, "Scan to open (PCD or PLY).", "file");
  const QCommandLineOption model({"m", "model"},
                                 "Taught model to open (.spmodel); repeat it for the views of one "
                                 "part, as with scanpick-cli recognize.",
                                 "file");
  const QCommandLineOption preset("preset", "Parameter preset to load (JSON).", "file");
  const QCommandLineOption recognize("recognize", "Recognize the model in the scene at start.");
  const QCommandLineOption screenshot("screenshot", "Save the 3D view as PNG when ready.", "png");
  const QCommandLineOption quit("quit-after-screenshot", "Exit after writing the screenshot.");
  parser.addOptions({scene, model, preset, recognize, screenshot, quit});
  parser.addPositionalArgument("files", "Scans or models to open.", "[files...]");
  parser.process(app);

  MainWindow window;
  window.resize(1400, 900);
  window.show();
  int exit_code = 0;
  try {
    if (parser.isSet(preset))
      window.parameterPanel()->loadPresetFile(parser.value(preset));
    if (parser.isSet(model) && !window.openModels(parser.values(model)))
      exit_code = 1;
    if (parser.isSet(scene)) {
      // Synchronous on purpose: scripted runs want the scene before anything else.
      const auto loaded =
          scanpick::core::loadCloud(parser.value(scene).toStdString(), std::nullopt);
      window.setScan(std::make_shared<const scanpick::core::PointCloud>(loaded.cloud),
                     parser.value(scene));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scanpick: %s\n", e.what());
    exit_code = 1;
  }
  QStringList models; // the views of one part
  for (const QString& file : parser.positionalArguments()) {
    if (file.endsWith(QLatin1String(".spmodel")))
      models << file;
    else
      window.openScan(file);
  }
  if (!models.isEmpty())
    window.openModels(models);
  if (exit_code != 0 && parser.isSet(quit))
    return exit_code;

  const QString shot = parser.value(screenshot);
  const bool quit_after = parser.isSet(quit);
  const auto take_screenshot = [&window, shot, quit_after](bool ok) {
    // A short delay lets the final frame reach the widget before it is grabbed.
    QTimer::singleShot(300, &window, [&window, shot, quit_after, ok] {
      const bool saved = shot.isEmpty() || window.saveScreenshot(shot);
      if (quit_after)
        QApplication::exit(saved && ok ? 0 : 1);
    });
  };
  if (parser.isSet(recognize)) {
    QObject::connect(&window, &MainWindow::recognitionFinished, &window, take_screenshot,
                     Qt::SingleShotConnection);
    QTimer::singleShot(0, &window, &MainWindow::recognize);
  } else if (!shot.isEmpty() || quit_after) {
    take_screenshot(true);
  }
  return QApplication::exec();
}
