#pragma once
/// @file Language.h
/// The application's language, switched while it runs: installing or removing the translators
/// makes Qt send QEvent::LanguageChange to every widget, which then sets its texts again
/// (TranslatedTexts). English is the source language; Italian comes from
/// translations/scanpick_it.ts, embedded as :/i18n/scanpick_it.qm, with Qt's own (qtbase_it) for
/// the standard dialogs and buttons when installed.

#include <QString>

namespace scanpick::ui {

/// Makes `code` the application's language (an unknown code means English): removes the
/// translators installed by an earlier call, installs those of `code`. Returns false, and leaves
/// the application in English, when the translation does not load. Needs a QCoreApplication.
bool applyLanguage(const QString& code);
/// The language applied last ("en" before any call).
QString currentLanguage();

} // namespace scanpick::ui
