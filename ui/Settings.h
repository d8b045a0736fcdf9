#pragma once
/// @file Settings.h
/// Every QSettings key of the application, in one place. QSettings holds UI state only (window
/// layout, recent files, last preset, last device, language); recipes and models are files.

#include <QString>

namespace scanpick::ui::settings {

inline const QString kGeometry = QStringLiteral("window/geometry"); ///< QByteArray
inline const QString kWindowState = QStringLiteral("window/state"); ///< docks, QByteArray
inline const QString kRecentFiles = QStringLiteral("files/recent"); ///< QStringList
inline const QString kLastDirectory = QStringLiteral("files/lastDirectory");
/// The preset file in effect; empty or absent: parameters derived from the part at teach.
inline const QString kLastPreset = QStringLiteral("params/lastPreset");  ///< preset file path
inline const QString kLastDevice = QStringLiteral("capture/lastDevice"); ///< device id
inline const QString kLanguage = QStringLiteral("ui/language");          ///< "en" or "it"
inline const QString kPointSize = QStringLiteral("view/pointSize");      ///< logical pixels

/// Most recent files kept in the File menu.
inline constexpr int kMaxRecentFiles = 8;

} // namespace scanpick::ui::settings
