#include "ui/panels/ResultsTable.h"

#include "ui/viewport/Presenters.h"

#include <QEvent>
#include <QHeaderView>
#include <QIcon>
#include <QPixmap>
#include <cmath>

namespace scanpick::ui {

ResultsTable::ResultsTable(QWidget* parent) : QTableWidget(parent) {
  setObjectName(QStringLiteral("resultsTable"));
  setColumnCount(6);
  setHeaderTexts();
  setColumnHidden(5, true);
  setSelectionBehavior(QAbstractItemView::SelectRows);
  setSelectionMode(QAbstractItemView::SingleSelection);
  setEditTriggers(QAbstractItemView::NoEditTriggers);
  horizontalHeader()->setStretchLastSection(true);
  verticalHeader()->setDefaultSectionSize(22);
  connect(this, &QTableWidget::itemSelectionChanged, this, [this] {
    const auto rows = selectionModel()->selectedRows();
    emit detectionSelected(rows.isEmpty() ? -1 : rows.first().row());
  });
}

void ResultsTable::setHeaderTexts() {
  setHorizontalHeaderLabels({tr("Score"), tr("Position x, y, z (mm)"),
                             tr("Orientation r, p, y (°)"), tr("Cluster"), tr("Grip points (mm)"),
                             tr("View")});
}

void ResultsTable::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange) {
    setHeaderTexts();
    // The rows' notes ("turn free", …) are made in setDetections; the selection stays.
    const int selected = currentRow();
    const auto detections = m_detections;
    const auto names = m_view_names;
    setDetections(detections, names);
    if (selected >= 0 && selected < rowCount()) {
      const QSignalBlocker block(this);
      selectRow(selected);
    }
  }
  QTableWidget::changeEvent(event);
}

void ResultsTable::setDetections(const std::vector<core::Detection>& detections,
                                 const QStringList& view_names) {
  const QSignalBlocker block(this);
  if (&detections != &m_detections) {
    m_detections = detections;
    m_view_names = view_names;
  }
  clearContents();
  setColumnHidden(5, view_names.size() < 2);
  setRowCount(static_cast<int>(detections.size()));
  const auto fmt = [](double v) { return QString::number(v, 'f', 1); };
  for (int row = 0; row < static_cast<int>(detections.size()); ++row) {
    const core::Detection& d = detections[row];
    const Eigen::Vector3d t = d.T_scene_model.translation();
    // Roll-pitch-yaw (X-Y-Z fixed axes): the convention robot controllers usually take.
    const Eigen::Vector3d ypr = d.T_scene_model.rotation().eulerAngles(2, 1, 0) * 180.0 / M_PI;
    QStringList grips;
    for (const core::GripPoint& g : d.grip_points_scene)
      grips << QStringLiteral("%1 (%2, %3, %4)")
                   .arg(QString::fromStdString(g.name), fmt(g.position_mm.x()),
                        fmt(g.position_mm.y()), fmt(g.position_mm.z()));
    setItem(row, 0, new QTableWidgetItem(QString::number(d.score, 'f', 3)));
    setItem(
        row, 1,
        new QTableWidgetItem(QStringLiteral("%1, %2, %3").arg(fmt(t.x()), fmt(t.y()), fmt(t.z()))));
    auto* orientation = new QTableWidgetItem(
        QStringLiteral("%1, %2, %3").arg(fmt(ypr[2]), fmt(ypr[1]), fmt(ypr[0])));
    if (d.free_turn_axis) {
      const Eigen::Vector3d& a = d.free_turn_axis->direction;
      orientation->setText(orientation->text() + QStringLiteral(" ") + tr("(turn free)"));
      orientation->setToolTip(tr("The view that found this part is round about its axis "
                                 "(direction %1, %2, %3), or round but for a detail this scan "
                                 "does not show (a cup's handle): its turn about that axis is not "
                                 "seen. Grip points on the axis are right.")
                                  .arg(QString::number(a.x(), 'f', 3),
                                       QString::number(a.y(), 'f', 3),
                                       QString::number(a.z(), 'f', 3)));
    }
    if (!d.alternative_poses.empty()) {
      orientation->setText(orientation->text() + QStringLiteral(" ") + tr("(turn unsure)"));
      orientation->setToolTip(
          tr("This scan cannot tell this pose from %n other pose(s) of the part: the view is "
             "nearly symmetric and the detail that tells them apart is hidden. Grip points that "
             "move between them must not be trusted.",
             nullptr, static_cast<int>(d.alternative_poses.size())));
    }
    setItem(row, 2, orientation);
    // The row's ID (1, 2, …) with the colour its detection has in the viewport, where the same
    // number labels it.
    QPixmap swatch(12, 12);
    swatch.fill(detectionColour(row));
    auto* id = new QTableWidgetItem(QIcon(swatch), QString::number(row + 1));
    id->setToolTip(tr("Detection %1: drawn in this colour, labelled %1 in the view").arg(row + 1));
    setVerticalHeaderItem(row, id);
    setItem(row, 3, new QTableWidgetItem(QString::number(d.cluster)));
    setItem(row, 4, new QTableWidgetItem(grips.join(QStringLiteral("; "))));
    if (d.model_index >= 0 && d.model_index < view_names.size())
      setItem(row, 5, new QTableWidgetItem(view_names[d.model_index]));
  }
  resizeColumnsToContents();
}

} // namespace scanpick::ui
