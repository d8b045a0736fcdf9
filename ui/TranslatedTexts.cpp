#include "ui/TranslatedTexts.h"

#include <QVariant>
#include <algorithm>

namespace scanpick::ui {

void TranslatedTexts::bind(QObject* target, const char* property, std::function<QString()> text) {
  const QByteArray name(property);
  QPointer<QObject> guarded(target);
  auto set = [guarded, name, text = std::move(text)] {
    if (guarded)
      guarded->setProperty(name.constData(), text());
  };
  set();
  const auto same = [&](const Entry& e) { return e.target == target && e.property == name; };
  if (const auto it = std::find_if(m_entries.begin(), m_entries.end(), same);
      it != m_entries.end()) {
    it->apply = std::move(set);
    return;
  }
  m_entries.push_back({guarded, name, std::move(set)});
}

void TranslatedTexts::bind(QObject* owner, std::function<void()> apply) {
  apply();
  m_entries.push_back({QPointer<QObject>(owner), QByteArray(), std::move(apply)});
}

void TranslatedTexts::apply() {
  // Entries of objects destroyed since go first.
  std::erase_if(m_entries, [](const Entry& e) { return e.target.isNull(); });
  // A bound function may bind again (replacing an entry), so iterate over a copy.
  const auto entries = m_entries;
  for (const Entry& e : entries)
    if (e.target)
      e.apply();
}

} // namespace scanpick::ui
