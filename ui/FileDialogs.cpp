#include "ui/FileDialogs.h"

#include <QFileDialog>

namespace scanpick::ui {

QString withSuffix(const QString& path, const QString& suffix) {
  if (path.isEmpty() || path.endsWith(QLatin1Char('.') + suffix, Qt::CaseInsensitive))
    return path;
  return path + QLatin1Char('.') + suffix;
}

QString askSaveFileName(QWidget* parent, const QString& title, const QString& directory,
                        const QString& filter, const QString& suffix) {
  QFileDialog dialog(parent, title, directory, filter);
  dialog.setObjectName(QStringLiteral("saveFileDialog"));
  dialog.setAcceptMode(QFileDialog::AcceptSave);
  dialog.setFileMode(QFileDialog::AnyFile);
  // The dialog's own default suffix makes its overwrite question name the real file.
  dialog.setDefaultSuffix(suffix);
  if (dialog.exec() != QDialog::Accepted || dialog.selectedFiles().isEmpty())
    return {};
  return withSuffix(dialog.selectedFiles().constFirst(), suffix);
}

} // namespace scanpick::ui
