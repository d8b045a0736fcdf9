// The QOpenGLWidget + vtkGenericOpenGLRenderWindow adapter: what VTK draws reaches the widget's
// framebuffer, the render size follows the widget, and mouse input reaches VTK's interactor.
#include "ui/viewport/QtVtkInteractor.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QImage>
#include <QMouseEvent>
#include <QTest>
#include <gtest/gtest.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

using scanpick::ui::QtVtkViewport;

namespace {

/// A viewport showing a red sphere filling about half its height on a black background.
struct RedSphereViewport {
  QtVtkViewport view;
  RedSphereViewport() {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(48);
    sphere->SetPhiResolution(48);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    // Pure emissive red, so lighting cannot change the colour checked below.
    actor->GetProperty()->SetColor(1, 0, 0);
    actor->GetProperty()->SetAmbient(1.0);
    actor->GetProperty()->SetDiffuse(0.0);
    actor->GetProperty()->SetSpecular(0.0);
    view.renderer()->GradientBackgroundOff();
    view.renderer()->SetBackground(0, 0, 0);
    view.renderer()->AddActor(actor);
    view.resize(400, 300);
    view.show();
    view.resetCamera();
  }
};

bool isRed(QRgb c) {
  return qRed(c) > 200 && qGreen(c) < 40 && qBlue(c) < 40;
}
bool isBlack(QRgb c) {
  return qRed(c) < 30 && qGreen(c) < 30 && qBlue(c) < 30;
}

void sendMouse(QWidget* w, QEvent::Type type, QPoint pos, Qt::MouseButton button,
               Qt::MouseButtons buttons) {
  QMouseEvent e(type, QPointF(pos), w->mapToGlobal(QPointF(pos)), button, buttons, Qt::NoModifier);
  QApplication::sendEvent(w, &e);
}

} // namespace

TEST(Viewport, DrawsRedSphereOnBlack) {
  RedSphereViewport fixture;
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&fixture.view));
  const QImage image = fixture.view.grabFramebuffer();
  ASSERT_FALSE(image.isNull());
  const double ratio = fixture.view.devicePixelRatioF();
  EXPECT_EQ(image.width(), qRound(400 * ratio));
  // The centre is on the sphere, a corner is background.
  const QRgb centre = image.pixel(image.width() / 2, image.height() / 2);
  const QRgb corner = image.pixel(3, 3);
  EXPECT_TRUE(isRed(centre)) << "centre " << qRed(centre) << "," << qGreen(centre) << ","
                             << qBlue(centre);
  EXPECT_TRUE(isBlack(corner)) << "corner " << qRed(corner) << "," << qGreen(corner) << ","
                               << qBlue(corner);
  EXPECT_GT(fixture.view.renderCount(), 0);
}

TEST(Viewport, RenderSizeFollowsResize) {
  RedSphereViewport fixture;
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&fixture.view));
  fixture.view.resize(520, 360);
  const double ratio = fixture.view.devicePixelRatioF();
  // The size reaches VTK in resizeGL, which Qt calls before the next paint.
  const QImage image = fixture.view.grabFramebuffer();
  const int* size = fixture.view.renderWindow()->GetSize();
  EXPECT_EQ(size[0], qRound(520 * ratio));
  EXPECT_EQ(size[1], qRound(360 * ratio));
  EXPECT_EQ(image.width(), qRound(520 * ratio));
  EXPECT_EQ(image.height(), qRound(360 * ratio));
  EXPECT_TRUE(isRed(image.pixel(image.width() / 2, image.height() / 2)));
}

TEST(Viewport, MouseDragRotatesCamera) {
  RedSphereViewport fixture;
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&fixture.view));
  (void)fixture.view.grabFramebuffer();
  vtkCamera* camera = fixture.view.renderer()->GetActiveCamera();
  double before[3];
  camera->GetPosition(before);
  const int frames_before = fixture.view.renderCount();

  // A left-button drag to the right: the trackball style orbits the camera around the sphere.
  QWidget* w = &fixture.view;
  sendMouse(w, QEvent::MouseButtonPress, {200, 150}, Qt::LeftButton, Qt::LeftButton);
  for (int x = 210; x <= 300; x += 10)
    sendMouse(w, QEvent::MouseMove, {x, 150}, Qt::NoButton, Qt::LeftButton);
  sendMouse(w, QEvent::MouseButtonRelease, {300, 150}, Qt::LeftButton, Qt::NoButton);

  double after[3];
  camera->GetPosition(after);
  const double moved = std::hypot(after[0] - before[0], after[1] - before[1], after[2] - before[2]);
  EXPECT_GT(moved, 0.1) << "camera did not move";
  // Same distance to the focal point: an orbit, not a zoom.
  EXPECT_NEAR(std::hypot(after[0], after[1], after[2]), std::hypot(before[0], before[1], before[2]),
              1e-3);
  EXPECT_GT(fixture.view.renderCount(), frames_before) << "interaction did not render";
  // Still a sphere in the middle after the orbit.
  const QImage image = fixture.view.grabFramebuffer();
  EXPECT_TRUE(isRed(image.pixel(image.width() / 2, image.height() / 2)));
}

TEST(Viewport, WheelZoomsIn) {
  RedSphereViewport fixture;
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&fixture.view));
  (void)fixture.view.grabFramebuffer();
  vtkCamera* camera = fixture.view.renderer()->GetActiveCamera();
  const double before = camera->GetDistance();
  // Two half notches make one VTK wheel event (accumulated to 120).
  for (int i = 0; i < 2; ++i) {
    QWheelEvent e(QPointF(200, 150), fixture.view.mapToGlobal(QPointF(200, 150)), QPoint(),
                  QPoint(0, 60), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(&fixture.view, &e);
  }
  EXPECT_LT(camera->GetDistance(), before);
}
