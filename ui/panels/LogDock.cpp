#include "ui/panels/LogDock.h"

#include "core/common/Log.h"

#include <QEvent>
#include <QPlainTextEdit>
#include <QPointer>
#include <QScrollBar>
#include <algorithm>
#include <mutex>
#include <spdlog/sinks/base_sink.h>

namespace scanpick::ui {

/// Formats messages on the logging thread and posts them to the dock's thread.
class QtLogSink : public spdlog::sinks::base_sink<std::mutex> {
public:
  explicit QtLogSink(LogDock* dock) : m_dock(dock) {}
  /// Stops forwarding; after it returns no new message is posted (same mutex as sink_it_).
  void detach() {
    std::lock_guard<std::mutex> lock(mutex_);
    m_dock = nullptr;
  }

protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    if (!m_dock)
      return;
    spdlog::memory_buf_t formatted;
    formatter_->format(msg, formatted);
    QString line = QString::fromUtf8(formatted.data(), static_cast<qsizetype>(formatted.size()));
    while (line.endsWith(QLatin1Char('\n')))
      line.chop(1);
    const int level = static_cast<int>(msg.level);
    // Queued: the dock is only touched on its own thread. A pending call to a destroyed dock
    // is dropped by Qt.
    QMetaObject::invokeMethod(
        m_dock, [dock = m_dock, level, line] { dock->appendLine(level, line); },
        Qt::QueuedConnection);
  }
  void flush_() override {}

private:
  LogDock* m_dock;
};

LogDock::LogDock(QWidget* parent)
    : QDockWidget(tr("Log"), parent), m_view(new QPlainTextEdit(this)) {
  setObjectName(QStringLiteral("LogDock"));
  m_view->setReadOnly(true);
  m_view->setMaximumBlockCount(5000);
  m_view->setFont(QFont(QStringLiteral("monospace")));
  setWidget(m_view);
  m_sink = std::make_shared<QtLogSink>(this);
  m_sink->set_pattern("%H:%M:%S.%e %l %v");
  core::logger()->sinks().push_back(m_sink);
}

void LogDock::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange)
    setWindowTitle(tr("Log"));
  QDockWidget::changeEvent(event);
}

LogDock::~LogDock() {
  m_sink->detach();
  auto& sinks = core::logger()->sinks();
  sinks.erase(std::remove(sinks.begin(), sinks.end(), m_sink), sinks.end());
}

void LogDock::appendLine(int level, const QString& text) {
  const char* colour = level >= spdlog::level::err    ? "#d04040"
                       : level == spdlog::level::warn ? "#c08000"
                                                      : nullptr;
  if (colour)
    m_view->appendHtml(QStringLiteral("<span style=\"color:%1\">%2</span>")
                           .arg(QLatin1String(colour), text.toHtmlEscaped()));
  else
    m_view->appendPlainText(text);
  m_view->verticalScrollBar()->setValue(m_view->verticalScrollBar()->maximum());
}

int LogDock::lineCount() const {
  // An empty document still has one (empty) block.
  return m_view->document()->isEmpty() ? 0 : m_view->document()->blockCount();
}

QString LogDock::text() const {
  return m_view->toPlainText();
}

} // namespace scanpick::ui
