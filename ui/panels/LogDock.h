#pragma once
/// @file LogDock.h
/// A dock showing the core's log. An spdlog sink added to core::logger() forwards each message
/// to the GUI thread with a queued invocation, so any thread may log.

#include <QDockWidget>
#include <memory>

class QPlainTextEdit;

namespace scanpick::ui {

class QtLogSink;

class LogDock : public QDockWidget {
  Q_OBJECT
public:
  explicit LogDock(QWidget* parent = nullptr);
  ~LogDock() override;

  /// Appends a line (GUI thread). `level` is an spdlog level (0 trace ... 5 critical).
  void appendLine(int level, const QString& text);
  /// Number of lines shown (for tests).
  [[nodiscard]] int lineCount() const;
  [[nodiscard]] QString text() const;

protected:
  /// The title follows a language switch.
  void changeEvent(QEvent* event) override;

private:
  QPlainTextEdit* m_view;
  std::shared_ptr<QtLogSink> m_sink;
};

} // namespace scanpick::ui
