#include "ui/viewport/QtVtkInteractor.h"

#include <QTimer>
#include <vtkCommand.h>
#include <vtkObjectFactory.h>

namespace scanpick::ui {

int QtVtkTimerHost::start(bool one_shot, unsigned long duration_ms) {
  const int id = m_next_id++;
  auto* timer = new QTimer(this);
  timer->setSingleShot(one_shot);
  timer->setInterval(static_cast<int>(duration_ms));
  connect(timer, &QTimer::timeout, this, [this, id] { m_interactor->onTimer(id); });
  m_timers[id] = timer;
  timer->start();
  return id;
}

void QtVtkTimerHost::stop(int platform_id) {
  const auto it = m_timers.find(platform_id);
  if (it == m_timers.end())
    return;
  it->second->stop();
  // deleteLater: a one-shot timer is destroyed from inside its own timeout handler.
  it->second->deleteLater();
  m_timers.erase(it);
}

vtkStandardNewMacro(QtVtkInteractor)

    QtVtkInteractor::QtVtkInteractor()
    : m_timers(this) {}

QtVtkInteractor::~QtVtkInteractor() = default;

void QtVtkInteractor::onTimer(int platform_id) {
  if (!GetEnabled())
    return;
  int vtk_id = GetVTKTimerId(platform_id);
  InvokeEvent(vtkCommand::TimerEvent, &vtk_id);
  // VTK keeps one-shot timers in its table until destroyed; Qt's single-shot timer has stopped.
  if (IsOneShotTimer(vtk_id))
    DestroyTimer(vtk_id);
}

int QtVtkInteractor::InternalCreateTimer(int /*timer_id*/, int timer_type, unsigned long duration) {
  return m_timers.start(timer_type == vtkRenderWindowInteractor::OneShotTimer, duration);
}

int QtVtkInteractor::InternalDestroyTimer(int platform_timer_id) {
  m_timers.stop(platform_timer_id);
  return 1;
}

} // namespace scanpick::ui
