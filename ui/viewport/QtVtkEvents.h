#pragma once
/// @file QtVtkEvents.h
/// Translation of Qt input events into VTK interactor events (what VTK's QVTKInteractorAdapter
/// does for its Qt5 widget).

class QEvent;
class vtkRenderWindowInteractor;

namespace scanpick::ui {

/// Forwards a mouse, wheel, key or enter/leave event to `interactor`. Positions are scaled by
/// `pixel_ratio` (device pixels) and Y is flipped (VTK's origin is bottom-left). Wheel deltas
/// accumulate in `wheel_accumulator` until they reach one notch (±120), as VTK expects.
/// Returns true when the event was one VTK understands.
bool forwardToVtk(vtkRenderWindowInteractor* interactor, QEvent* event, double pixel_ratio,
                  int& wheel_accumulator);

} // namespace scanpick::ui
