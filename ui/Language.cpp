#include "ui/Language.h"

#include <QCoreApplication>
#include <QLibraryInfo>
#include <QPointer>
#include <QTranslator>

namespace scanpick::ui {
namespace {

struct Installed {
  QPointer<QTranslator> own, qt; // children of the application object
  QString code = QStringLiteral("en");
};

Installed& installed() {
  static Installed state;
  return state;
}

} // namespace

bool applyLanguage(const QString& code) {
  Installed& state = installed();
  for (QPointer<QTranslator>* t : {&state.own, &state.qt})
    if (*t) {
      QCoreApplication::removeTranslator(*t);
      delete t->data();
    }
  state.code = QStringLiteral("en");
  if (code != QLatin1String("it"))
    return code == QLatin1String("en");
  auto* own = new QTranslator(QCoreApplication::instance());
  if (!own->load(QStringLiteral(":/i18n/scanpick_it.qm"))) {
    delete own;
    return false;
  }
  QCoreApplication::installTranslator(own);
  state.own = own;
  // Qt's own texts (standard buttons, file dialogs), when the system has them.
  auto* qt = new QTranslator(QCoreApplication::instance());
  if (qt->load(QStringLiteral("qtbase_it"), QLibraryInfo::path(QLibraryInfo::TranslationsPath))) {
    QCoreApplication::installTranslator(qt);
    state.qt = qt;
  } else {
    delete qt;
  }
  state.code = code;
  return true;
}

QString currentLanguage() {
  return installed().code;
}

} // namespace scanpick::ui
