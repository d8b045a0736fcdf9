#include "ui/viewport/QtVtkViewport.h"

#include "ui/viewport/QtVtkEvents.h"
#include "ui/viewport/QtVtkInteractor.h"

#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLState.h>
#include <vtkRenderer.h>

namespace scanpick::ui {

QtVtkViewport::QtVtkViewport(QWidget* parent) : QOpenGLWidget(parent) {
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true); // hover highlighting of 3D widgets
  setMinimumSize(160, 120);
  // Qt owns the context; VTK renders into its own framebuffers that paintGL blits.
  m_render_window->SetReadyForRendering(false);
  m_render_window->SetFrameBlitModeToNoBlit();
  m_render_window->SetMultiSamples(0);
  m_render_window->SetOwnContext(false);
  for (const unsigned long id :
       {vtkCommand::WindowMakeCurrentEvent, vtkCommand::WindowIsCurrentEvent,
        vtkCommand::WindowFrameEvent, vtkCommand::WindowSupportsOpenGLEvent,
        vtkCommand::WindowIsDirectEvent})
    m_render_window->AddObserver(id, this, &QtVtkViewport::onRenderWindowEvent);

  m_renderer->SetBackground(0.11, 0.12, 0.14);
  m_renderer->SetBackground2(0.28, 0.30, 0.34);
  m_renderer->GradientBackgroundOn();
  m_render_window->AddRenderer(m_renderer);

  m_interactor = vtkSmartPointer<QtVtkInteractor>::New();
  m_interactor->SetRenderWindow(m_render_window);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  m_interactor->SetInteractorStyle(style);
  m_interactor->Initialize();
}

QtVtkViewport::~QtVtkViewport() {
  // Release GL resources while the context still exists, then detach the observers that point
  // back at this widget.
  if (m_gl_ready) {
    makeCurrent();
    cleanupContext();
  }
  // QOpenGLWidget's destructor destroys the context after this one has run: its
  // aboutToBeDestroyed must no longer reach cleanupContext of a widget that is no longer a
  // QtVtkViewport.
  if (context() != nullptr)
    disconnect(context(), nullptr, this, nullptr);
  m_render_window->RemoveAllObservers();
}

QSurfaceFormat QtVtkViewport::defaultFormat() {
  QSurfaceFormat format;
  format.setRenderableType(QSurfaceFormat::OpenGL);
  format.setVersion(3, 2);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
  format.setRedBufferSize(8);
  format.setGreenBufferSize(8);
  format.setBlueBufferSize(8);
  format.setDepthBufferSize(24);
  format.setAlphaBufferSize(8);
  format.setStencilBufferSize(0);
  format.setSamples(0);
  return format;
}

vtkGenericOpenGLRenderWindow* QtVtkViewport::renderWindow() const {
  return m_render_window;
}
vtkRenderer* QtVtkViewport::renderer() const {
  return m_renderer;
}
QtVtkInteractor* QtVtkViewport::interactor() const {
  return m_interactor;
}

void QtVtkViewport::requestRender() {
  m_needs_render = true;
  update();
}

void QtVtkViewport::resetCamera() {
  m_renderer->ResetCamera();
  m_renderer->ResetCameraClippingRange();
  requestRender();
}

void QtVtkViewport::onRenderWindowEvent(vtkObject* /*caller*/, unsigned long event_id,
                                        void* call_data) {
  QOpenGLContext* ctx = context();
  switch (event_id) {
  case vtkCommand::WindowMakeCurrentEvent:
    // The context's own surface, not QOpenGLWidget::makeCurrent(): that would bind Qt's FBO
    // behind VTK's state cache (platform notes, trap 4 point 2).
    if (ctx)
      ctx->makeCurrent(ctx->surface());
    break;
  case vtkCommand::WindowIsCurrentEvent: {
    QOpenGLContext* current = QOpenGLContext::currentContext();
    *static_cast<bool*>(call_data) = ctx && current == ctx && current->surface() == ctx->surface();
    break;
  }
  case vtkCommand::WindowSupportsOpenGLEvent:
  case vtkCommand::WindowIsDirectEvent:
    *static_cast<int*>(call_data) = 1;
    break;
  case vtkCommand::WindowFrameEvent:
    ++m_render_count;
    // A render outside paintGL (interaction, 3D widgets): its image is fresh, just show it.
    if (!m_in_paint) {
      m_needs_render = false;
      update();
    }
    break;
  default:
    break;
  }
}

void QtVtkViewport::initializeGL() {
  // Runs again when the widget moves to another top-level window (new context).
  auto* state = m_render_window->GetState();
  state->Reset();
  state->vtkglDepthFunc(GL_LEQUAL); // Qt leaves GL_LESS
  m_render_window->SetOwnContext(false);
  m_render_window->SetReadyForRendering(true);
  m_render_window->OpenGLInitContext();
  m_render_window->SetFrameBlitModeToNoBlit();
  m_gl_ready = true;
  m_needs_render = true;
  updateSize();
  connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &QtVtkViewport::cleanupContext,
          static_cast<Qt::ConnectionType>(Qt::DirectConnection | Qt::UniqueConnection));
}

void QtVtkViewport::cleanupContext() {
  if (!m_gl_ready)
    return;
  m_render_window->Finalize();
  m_render_window->SetReadyForRendering(false);
  m_gl_ready = false;
}

void QtVtkViewport::updateSize() {
  const int w = qMax(1, qRound(width() * ratio()));
  const int h = qMax(1, qRound(height() * ratio()));
  m_render_window->SetDPI(qRound(72 * ratio()));
  m_render_window->SetSize(w, h);
  m_interactor->UpdateSize(w, h);
}

void QtVtkViewport::resizeGL(int /*width*/, int /*height*/) {
  updateSize();
  m_needs_render = true;
}

void QtVtkViewport::paintGL() {
  auto* gl = context()->extraFunctions();
  if (!m_gl_ready) {
    gl->glClearColor(0, 0, 0, 1);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    return;
  }
  if (m_needs_render) {
    auto* state = m_render_window->GetState();
    state->Reset();
    state->Push();
    state->vtkglDepthFunc(GL_LEQUAL);
    m_in_paint = true;
    m_render_window->Render();
    m_in_paint = false;
    m_needs_render = false;
    state->Pop();
  }
  // Rendering may have made the context current on another surface (progress events painting
  // other widgets); bind the widget's framebuffer again before blitting into it.
  makeCurrent();
  vtkOpenGLFramebufferObject* display = m_render_window->GetDisplayFramebuffer();
  const int* size = m_render_window->GetSize();
  if (!display || display->GetFBOIndex() == 0) {
    gl->glClearColor(0, 0, 0, 1);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    return;
  }
  const GLuint target = defaultFramebufferObject();
  gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, display->GetFBOIndex());
  gl->glReadBuffer(GL_COLOR_ATTACHMENT0);
  gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target);
  gl->glDisable(GL_SCISSOR_TEST);
  const int w = qRound(width() * ratio()), h = qRound(height() * ratio());
  gl->glBlitFramebuffer(0, 0, size[0], size[1], 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  // VTK may leave alpha below 1, which Qt would composite as translucency.
  gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  gl->glClearColor(0, 0, 0, 1);
  gl->glClear(GL_COLOR_BUFFER_BIT);
  gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl->glBindFramebuffer(GL_FRAMEBUFFER, target);
}

bool QtVtkViewport::event(QEvent* event) {
  // Events forwarded to VTK still reach QOpenGLWidget, so Qt's own handling (focus) runs too.
  if (m_interactor)
    forwardToVtk(m_interactor, event, ratio(), m_wheel_accumulator);
  return QOpenGLWidget::event(event);
}

} // namespace scanpick::ui
