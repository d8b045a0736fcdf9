#include "ui/panels/DevicePanel.h"

#include "core/common/Log.h"
#include "ui/Settings.h"
#include "ui/jobs/JobRunner.h"

#include <QEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSettings>
#include <QVBoxLayout>

#ifdef SCANPICK_UI_WITH_DEVICES
#include "devices/CameraRegistry.h"
#include "devices/usb/UsbMonitor.h"
#endif

namespace scanpick::ui {

#ifdef SCANPICK_UI_WITH_DEVICES
namespace {
using DeviceList = std::vector<devices::DeviceInfo>;
}
#endif

DevicePanel::DevicePanel(QWidget* parent) : QWidget(parent) {
  m_jobs = new JobRunner(this);
  m_enumerate = new JobRunner(this);
  auto* layout = new QVBoxLayout(this);
  m_list = new QListWidget(this);
  m_list->setObjectName(QStringLiteral("deviceList"));
  layout->addWidget(m_list, 1);
  m_id = new QLineEdit(this);
  m_id->setObjectName(QStringLiteral("deviceId"));
  m_texts.bind(m_id, "placeholderText",
               [] { return tr("device id, e.g. kinect:0 or file:/path/scan.pcd"); });
  m_id->setText(QSettings().value(settings::kLastDevice).toString());
  layout->addWidget(m_id);
  auto* row = new QHBoxLayout;
  auto* refresh_button = new QPushButton(this);
  m_open = new QPushButton(this);
  m_capture = new QPushButton(this);
  m_stream = new QPushButton(this);
  m_texts.bind(refresh_button, "text", [] { return tr("Refresh"); });
  m_texts.bind(m_capture, "text", [] { return tr("Capture"); });
  m_texts.bind(m_stream, "text", [] { return tr("Stream"); });
  m_stream->setCheckable(true);
  m_open->setObjectName(QStringLiteral("openDeviceButton"));
  m_capture->setObjectName(QStringLiteral("captureButton"));
  m_stream->setObjectName(QStringLiteral("streamButton"));
  refresh_button->setObjectName(QStringLiteral("refreshDevicesButton"));
  for (QPushButton* b : {refresh_button, m_open, m_capture, m_stream})
    row->addWidget(b);
  layout->addLayout(row);
  m_state = new QLabel(this);
  m_state->setObjectName(QStringLiteral("deviceState"));
  m_state->setWordWrap(true);
  layout->addWidget(m_state);

  connect(m_list, &QListWidget::currentTextChanged, this, [this] {
    if (auto* item = m_list->currentItem())
      m_id->setText(item->data(Qt::UserRole).toString());
  });
  connect(refresh_button, &QPushButton::clicked, this, &DevicePanel::refresh);
  connect(m_open, &QPushButton::clicked, this, [this] {
    if (m_camera)
      closeDevice();
    else
      openDevice(m_id->text().trimmed());
  });
  connect(m_capture, &QPushButton::clicked, this, &DevicePanel::captureOne);
  connect(m_stream, &QPushButton::toggled, this, &DevicePanel::setStreaming);

#ifdef SCANPICK_UI_WITH_DEVICES
  try {
    // Plug/unplug arrives on the monitor thread; the refresh is queued to the GUI thread.
    m_usb = std::make_unique<devices::UsbMonitor>([this](const devices::UsbEvent&) {
      QMetaObject::invokeMethod(this, &DevicePanel::refresh, Qt::QueuedConnection);
    });
  } catch (const std::exception& e) {
    core::logger()->warn("USB plug/unplug monitoring is off: {}", e.what());
  }
  refresh();
#else
  setStateText([] { return tr("This build has no camera support (SCANPICK_BUILD_DEVICES=OFF)."); });
  setEnabled(false);
#endif
  updateButtons();
}

DevicePanel::~DevicePanel() {
#ifdef SCANPICK_UI_WITH_DEVICES
  m_usb.reset();
  if (m_camera && m_camera->isStreaming())
    m_camera->stopStream();
#endif
}

QString DevicePanel::stateText() const {
  return m_state->text();
}

void DevicePanel::setStateText(std::function<QString()> text) {
  m_texts.bind(m_state, "text", std::move(text));
}

void DevicePanel::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange)
    m_texts.apply();
  QWidget::changeEvent(event);
}

void DevicePanel::updateButtons() {
  m_texts.bind(m_open, "text",
               [open = m_camera != nullptr] { return open ? tr("Close") : tr("Open"); });
  m_capture->setEnabled(m_camera != nullptr && !m_stream->isChecked());
  m_stream->setEnabled(m_camera != nullptr);
}

void DevicePanel::refresh() {
#ifdef SCANPICK_UI_WITH_DEVICES
  setStateText([] { return tr("Looking for cameras…"); });
  m_enumerate->run<std::pair<DeviceList, std::vector<std::string>>>(
      [](const core::ProgressFn&) {
        std::vector<std::string> warnings;
        DeviceList list = devices::enumerateDevices({}, &warnings);
        return std::pair{std::move(list), std::move(warnings)};
      },
      [this](std::shared_ptr<const std::pair<DeviceList, std::vector<std::string>>> found) {
        m_list->clear();
        for (const devices::DeviceInfo& d : found->first) {
          auto* item = new QListWidgetItem(
              QStringLiteral("%1 — %2%3")
                  .arg(QString::fromStdString(d.model), QString::fromStdString(d.id),
                       d.note.empty()
                           ? QString()
                           : QStringLiteral(" (%1)").arg(QString::fromStdString(d.note))),
              m_list);
          item->setData(Qt::UserRole, QString::fromStdString(d.id));
        }
        for (const std::string& w : found->second)
          core::logger()->info("camera search: {}", w);
        setStateText([n = found->first.size()] {
          return n == 0 ? tr("No camera attached. A file:<path> id replays saved scans.")
                        : tr("%1 camera(s) found").arg(n);
        });
        emit devicesListed(static_cast<int>(found->first.size()));
      },
      [this](const QString& e) { setStateText([e] { return e; }); });
#endif
}

void DevicePanel::openDevice(const QString& id) {
#ifdef SCANPICK_UI_WITH_DEVICES
  if (id.isEmpty()) {
    emit deviceError(tr("Choose a camera in the list or type its id."));
    return;
  }
  setStateText([id] { return tr("Opening %1…").arg(id); });
  const std::string sid = id.toStdString();
  m_jobs->run<std::shared_ptr<devices::Camera>>(
      [sid](const core::ProgressFn&) {
        return std::shared_ptr<devices::Camera>(devices::openCamera(sid));
      },
      [this, id](std::shared_ptr<const std::shared_ptr<devices::Camera>> camera) {
        m_camera = *camera;
        QSettings().setValue(settings::kLastDevice, id);
        setStateText([model = QString::fromStdString(m_camera->info().model)] {
          return tr("Open: %1").arg(model);
        });
        core::logger()->info("camera {} open", id.toStdString());
        updateButtons();
        emit cameraOpened(id);
      },
      [this](const QString& e) {
        setStateText([e] { return e; });
        emit deviceError(e);
      });
#else
  Q_UNUSED(id);
#endif
}

void DevicePanel::closeDevice() {
#ifdef SCANPICK_UI_WITH_DEVICES
  if (m_stream->isChecked())
    m_stream->setChecked(false);
  m_camera.reset();
  setStateText([] { return tr("Closed"); });
  updateButtons();
#endif
}

void DevicePanel::captureOne() {
#ifdef SCANPICK_UI_WITH_DEVICES
  if (!m_camera)
    return;
  auto camera = m_camera;
  m_jobs->run<devices::Frame>(
      [camera](const core::ProgressFn&) { return camera->capture(std::chrono::seconds(5)); },
      [this](std::shared_ptr<const devices::Frame> frame) {
        emit frameCaptured(std::make_shared<const core::PointCloud>(frame->cloud),
                           tr("capture %1").arg(frame->metadata.frame_index));
      },
      [this](const QString& e) {
        setStateText([e] { return e; });
        emit deviceError(e);
      });
#endif
}

void DevicePanel::setStreaming(bool on) {
#ifdef SCANPICK_UI_WITH_DEVICES
  if (!m_camera)
    return;
  try {
    if (!on) {
      m_camera->stopStream();
    } else if (!m_camera->isStreaming()) {
      m_camera->startStream(
          [this](const devices::Frame& frame) {
            // Device thread: hand over an immutable copy; skip frames while one is pending.
            auto cloud = std::make_shared<const core::PointCloud>(frame.cloud);
            const QString name = tr("stream %1").arg(frame.metadata.frame_index);
            QMetaObject::invokeMethod(
                this, [this, cloud, name] { emit frameCaptured(cloud, name); },
                Qt::QueuedConnection);
          },
          [this](const devices::DeviceError& error) {
            const QString message = QString::fromUtf8(error.what());
            QMetaObject::invokeMethod(
                this,
                [this, message] {
                  m_stream->setChecked(false);
                  setStateText([message] { return message; });
                  emit deviceError(message);
                },
                Qt::QueuedConnection);
          },
          std::chrono::seconds(5));
    }
  } catch (const std::exception& e) {
    emit deviceError(QString::fromUtf8(e.what()));
  }
  updateButtons();
#else
  Q_UNUSED(on);
#endif
}

} // namespace scanpick::ui
