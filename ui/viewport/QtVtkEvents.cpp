#include "ui/viewport/QtVtkEvents.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QWheelEvent>
#include <cmath>
#include <vtkCommand.h>
#include <vtkRenderWindowInteractor.h>

namespace scanpick::ui {
namespace {

/// VTK key symbol (X11 names) of a non-printing Qt key, or nullptr.
const char* keySym(int key) {
  switch (key) {
  case Qt::Key_Left:
    return "Left";
  case Qt::Key_Right:
    return "Right";
  case Qt::Key_Up:
    return "Up";
  case Qt::Key_Down:
    return "Down";
  case Qt::Key_PageUp:
    return "Prior";
  case Qt::Key_PageDown:
    return "Next";
  case Qt::Key_Home:
    return "Home";
  case Qt::Key_End:
    return "End";
  case Qt::Key_Escape:
    return "Escape";
  case Qt::Key_Return:
    return "Return";
  case Qt::Key_Enter:
    return "KP_Enter";
  case Qt::Key_Tab:
    return "Tab";
  case Qt::Key_Backspace:
    return "BackSpace";
  case Qt::Key_Delete:
    return "Delete";
  case Qt::Key_Insert:
    return "Insert";
  case Qt::Key_Space:
    return "space";
  case Qt::Key_Shift:
    return "Shift_L";
  case Qt::Key_Control:
    return "Control_L";
  case Qt::Key_Alt:
    return "Alt_L";
  default:
    return nullptr;
  }
}

void setPosition(vtkRenderWindowInteractor* iren, const QPointF& pos, double ratio,
                 Qt::KeyboardModifiers mods, int repeat) {
  iren->SetEventInformationFlipY(static_cast<int>(std::lround(pos.x() * ratio)),
                                 static_cast<int>(std::lround(pos.y() * ratio)),
                                 (mods & Qt::ControlModifier) ? 1 : 0,
                                 (mods & Qt::ShiftModifier) ? 1 : 0, 0, repeat);
  iren->SetAltKey((mods & Qt::AltModifier) ? 1 : 0);
}

unsigned long buttonEvent(Qt::MouseButton button, bool press) {
  switch (button) {
  case Qt::LeftButton:
    return press ? vtkCommand::LeftButtonPressEvent : vtkCommand::LeftButtonReleaseEvent;
  case Qt::MiddleButton:
    return press ? vtkCommand::MiddleButtonPressEvent : vtkCommand::MiddleButtonReleaseEvent;
  case Qt::RightButton:
    return press ? vtkCommand::RightButtonPressEvent : vtkCommand::RightButtonReleaseEvent;
  default:
    return vtkCommand::NoEvent;
  }
}

} // namespace

bool forwardToVtk(vtkRenderWindowInteractor* iren, QEvent* event, double ratio,
                  int& wheel_accumulator) {
  if (!iren || !iren->GetEnabled())
    return false;
  switch (event->type()) {
  case QEvent::MouseButtonPress:
  case QEvent::MouseButtonDblClick:
  case QEvent::MouseButtonRelease:
  case QEvent::MouseMove: {
    auto* e = static_cast<QMouseEvent*>(event);
    const bool dbl = event->type() == QEvent::MouseButtonDblClick;
    setPosition(iren, e->position(), ratio, e->modifiers(), dbl ? 1 : 0);
    if (event->type() == QEvent::MouseMove) {
      iren->InvokeEvent(vtkCommand::MouseMoveEvent, e);
      return true;
    }
    const unsigned long id = buttonEvent(e->button(), event->type() != QEvent::MouseButtonRelease);
    if (id == vtkCommand::NoEvent)
      return false;
    iren->InvokeEvent(id, e);
    return true;
  }
  case QEvent::Wheel: {
    auto* e = static_cast<QWheelEvent*>(event);
    setPosition(iren, e->position(), ratio, e->modifiers(), 0);
    const QPoint delta = e->angleDelta();
    wheel_accumulator += delta.y() != 0 ? delta.y() : delta.x();
    // One VTK wheel event per full notch; touchpads send many small deltas.
    while (wheel_accumulator >= 120) {
      wheel_accumulator -= 120;
      iren->InvokeEvent(vtkCommand::MouseWheelForwardEvent, e);
    }
    while (wheel_accumulator <= -120) {
      wheel_accumulator += 120;
      iren->InvokeEvent(vtkCommand::MouseWheelBackwardEvent, e);
    }
    return true;
  }
  case QEvent::KeyPress:
  case QEvent::KeyRelease: {
    auto* e = static_cast<QKeyEvent*>(event);
    const QString text = e->text();
    const char ascii = text.size() == 1 && text.at(0).unicode() < 128
                           ? static_cast<char>(text.at(0).unicode())
                           : '\0';
    const QByteArray printable = ascii > 32 ? QByteArray(1, ascii) : QByteArray();
    const char* sym = printable.isEmpty() ? keySym(e->key()) : printable.constData();
    const auto mods = e->modifiers();
    iren->SetKeyEventInformation((mods & Qt::ControlModifier) ? 1 : 0,
                                 (mods & Qt::ShiftModifier) ? 1 : 0, ascii,
                                 e->isAutoRepeat() ? 1 : 0, sym ? sym : "None");
    iren->SetAltKey((mods & Qt::AltModifier) ? 1 : 0);
    if (event->type() == QEvent::KeyPress) {
      iren->InvokeEvent(vtkCommand::KeyPressEvent, e);
      if (ascii)
        iren->InvokeEvent(vtkCommand::CharEvent, e);
    } else {
      iren->InvokeEvent(vtkCommand::KeyReleaseEvent, e);
    }
    return true;
  }
  case QEvent::Enter:
    iren->InvokeEvent(vtkCommand::EnterEvent, event);
    return true;
  case QEvent::Leave:
    iren->InvokeEvent(vtkCommand::LeaveEvent, event);
    return true;
  default:
    return false;
  }
}

} // namespace scanpick::ui
