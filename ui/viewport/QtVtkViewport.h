#pragma once
/// @file QtVtkViewport.h
/// A QOpenGLWidget hosting a vtkGenericOpenGLRenderWindow: the Qt6 replacement for VTK's
/// Qt5-only QVTKOpenGLNativeWidget (see the platform notes, trap 4). VTK renders into its own
/// framebuffer in the widget's context; paintGL blits that into the widget's framebuffer.
/// Everything here runs on the GUI thread.

#include <QOpenGLWidget>
#include <QSurfaceFormat>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

class vtkGenericOpenGLRenderWindow;
class vtkRenderer;
class vtkObject;

namespace scanpick::ui {

class QtVtkInteractor;

/// The 3D viewport. Owns a render window, one renderer (dark background) and an interactor with
/// the trackball-camera style.
class QtVtkViewport : public QOpenGLWidget {
  Q_OBJECT
public:
  explicit QtVtkViewport(QWidget* parent = nullptr);
  ~QtVtkViewport() override;

  /// The surface format VTK needs: OpenGL 3.2 core, no multisampling (VTK multisamples in its own
  /// framebuffer). Set it with QSurfaceFormat::setDefaultFormat() before creating QApplication.
  static QSurfaceFormat defaultFormat();

  [[nodiscard]] vtkGenericOpenGLRenderWindow* renderWindow() const;
  [[nodiscard]] vtkRenderer* renderer() const;
  [[nodiscard]] QtVtkInteractor* interactor() const;

  /// Asks for a repaint that re-renders the VTK scene (after changing actors or the camera).
  void requestRender();
  /// Fits the camera to the visible actors and re-renders.
  void resetCamera();
  /// Number of frames VTK rendered (for tests and diagnostics).
  [[nodiscard]] int renderCount() const { return m_render_count; }

protected:
  void initializeGL() override;
  void resizeGL(int width, int height) override;
  void paintGL() override;
  bool event(QEvent* event) override;

private:
  void onRenderWindowEvent(vtkObject* caller, unsigned long event_id, void* call_data);
  void cleanupContext();
  void updateSize();
  [[nodiscard]] double ratio() const { return devicePixelRatioF(); }

  vtkNew<vtkGenericOpenGLRenderWindow> m_render_window;
  vtkNew<vtkRenderer> m_renderer;
  vtkSmartPointer<QtVtkInteractor> m_interactor;
  bool m_in_paint = false;
  bool m_needs_render = true;
  bool m_gl_ready = false;
  int m_render_count = 0;
  int m_wheel_accumulator = 0;
};

} // namespace scanpick::ui
