#pragma once
/// @file QtVtkInteractor.h
/// A vtkRenderWindowInteractor for a Qt event loop: VTK timers are QTimers (3D widgets such as
/// vtkBoxWidget2 need them) and Start() runs no loop of its own, since Qt's loop is running.

#include <QObject>
#include <map>
#include <vtkRenderWindowInteractor.h>

class QTimer;

namespace scanpick::ui {

class QtVtkInteractor;

/// Owns the QTimers of one QtVtkInteractor and forwards their timeouts.
class QtVtkTimerHost : public QObject {
  Q_OBJECT
public:
  explicit QtVtkTimerHost(QtVtkInteractor* interactor) : m_interactor(interactor) {}
  int start(bool one_shot, unsigned long duration_ms);
  void stop(int platform_id);

private:
  QtVtkInteractor* m_interactor;
  std::map<int, QTimer*> m_timers;
  int m_next_id = 1;
};

/// The interactor used by QtVtkViewport. Events are fed to it by the viewport; it never blocks.
class QtVtkInteractor : public vtkRenderWindowInteractor {
public:
  static QtVtkInteractor* New();
  vtkTypeMacro(QtVtkInteractor, vtkRenderWindowInteractor)

      /// Called by the timer host when a Qt timer fires.
      void onTimer(int platform_id);

protected:
  QtVtkInteractor();
  ~QtVtkInteractor() override;
  int InternalCreateTimer(int timer_id, int timer_type, unsigned long duration) override;
  int InternalDestroyTimer(int platform_timer_id) override;
  void StartEventLoop() override {}
  void TerminateApp() override {}

private:
  QtVtkInteractor(const QtVtkInteractor&) = delete;
  void operator=(const QtVtkInteractor&) = delete;
  QtVtkTimerHost m_timers;
};

} // namespace scanpick::ui
