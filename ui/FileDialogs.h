#pragma once
/// @file FileDialogs.h
/// File names the application writes: the extension its readers look for is added when the
/// operator leaves it out, so that File → Open takes the file back.

#include <QString>

class QWidget;

namespace scanpick::ui {

/// `path` ending in ".`suffix`" (case-insensitive), `suffix` appended otherwise ("model" →
/// "model.spmodel", "model.txt" → "model.txt.spmodel"). An empty path stays empty.
QString withSuffix(const QString& path, const QString& suffix);

/// Asks for a file to write (a modal save dialog starting in `directory`, or at the file it
/// names). `filter` as QFileDialog takes it; `suffix` is added as withSuffix() does. Returns the
/// path, or an empty string when the operator cancelled.
QString askSaveFileName(QWidget* parent, const QString& title, const QString& directory,
                        const QString& filter, const QString& suffix);

} // namespace scanpick::ui
