#pragma once
/// @file DevicePanel.h
/// Capture: the list of attached cameras (refreshed on USB plug/unplug), open by id (also
/// "file:<path>" replays), single shot or live stream. Device calls run off the GUI thread;
/// frames and errors come back through queued invocations. Errors are shown, never fatal.

#include "core/cloud/PointCloud.h"
#include "ui/TranslatedTexts.h"

#include <QWidget>
#include <memory>

class QLabel;
class QLineEdit;
class QListWidget;
class QPushButton;

namespace scanpick::devices {
class Camera;
class UsbMonitor;
} // namespace scanpick::devices

namespace scanpick::ui {

class JobRunner;

class DevicePanel : public QWidget {
  Q_OBJECT
public:
  explicit DevicePanel(QWidget* parent = nullptr);
  ~DevicePanel() override;

  /// The open camera, or null. Shared so background jobs keep it alive while they use it.
  [[nodiscard]] std::shared_ptr<devices::Camera> camera() const { return m_camera; }
  /// Opens the camera with `id` in the background; emits cameraOpened or deviceError.
  void openDevice(const QString& id);
  void closeDevice();
  /// Captures one frame in the background; emits frameCaptured or deviceError.
  void captureOne();
  void setStreaming(bool on);
  /// Re-enumerates the devices in the background; emits devicesListed when done.
  void refresh();
  /// What the panel says about the devices (found, opening, open, last error).
  [[nodiscard]] QString stateText() const;

signals:
  void frameCaptured(std::shared_ptr<const scanpick::core::PointCloud> cloud, const QString& name);
  void cameraOpened(const QString& id);
  void deviceError(const QString& message);
  /// The device list was refreshed (`count` cameras found).
  void devicesListed(int count);

protected:
  /// Texts follow a language switch.
  void changeEvent(QEvent* event) override;

private:
  void updateButtons();
  /// Shows `text()` as the panel's state, in the language of the moment.
  void setStateText(std::function<QString()> text);

  QListWidget* m_list = nullptr;
  QLineEdit* m_id = nullptr;
  QPushButton* m_open = nullptr;
  QPushButton* m_capture = nullptr;
  QPushButton* m_stream = nullptr;
  QLabel* m_state = nullptr;
  JobRunner* m_jobs = nullptr;
  JobRunner* m_enumerate = nullptr;
  std::shared_ptr<devices::Camera> m_camera;
  std::unique_ptr<devices::UsbMonitor> m_usb;
  TranslatedTexts m_texts;
};

} // namespace scanpick::ui
