#pragma once
/// @file TranslatedTexts.h
/// Live language switching (the retranslateUi pattern without a .ui file): a widget binds each
/// text it shows to a function that makes it with tr(), and calls apply() from its
/// changeEvent(QEvent::LanguageChange), which Qt sends after a translator is installed or removed
/// (ui/Language.h). Texts that depend on data (a count, a file name) are bound the same way, so
/// that they follow the language as well. GUI thread only.

#include <QByteArray>
#include <QObject>
#include <QPointer>
#include <QString>
#include <functional>
#include <vector>

namespace scanpick::ui {

class TranslatedTexts {
public:
  /// Sets `target`'s `property` ("text", "toolTip", "title", "windowTitle", "placeholderText",
  /// …) to `text()` now and at every apply() while `target` lives. Binding the same target and
  /// property again replaces the earlier binding.
  void bind(QObject* target, const char* property, std::function<QString()> text);
  /// Calls `apply` now and at every apply() while `owner` lives (list items, headers, …).
  void bind(QObject* owner, std::function<void()> apply);
  /// Sets every bound text again, in the language now installed.
  void apply();

private:
  struct Entry {
    QPointer<QObject> target;
    QByteArray property; // empty for a bound function
    std::function<void()> apply;
  };
  std::vector<Entry> m_entries;
};

} // namespace scanpick::ui
