#pragma once
/// @file ResultsTable.h
/// The detections of the last recognition: score, position, orientation (roll, pitch, yaw) and
/// grip points, one row per detection, best first. Selecting a row highlights that detection.

#include "core/model/TaughtModel.h"
#include "core/pipeline/Detection.h"

#include <QTableWidget>
#include <vector>

namespace scanpick::ui {

class ResultsTable : public QTableWidget {
  Q_OBJECT
public:
  explicit ResultsTable(QWidget* parent = nullptr);
  /// Shows `detections` (row i = detection i). `model` may be null.
  void setDetections(const std::vector<core::Detection>& detections, const core::TaughtModel* model);

signals:
  /// Row selected (-1 when the selection was cleared).
  void detectionSelected(int row);
};

} // namespace scanpick::ui
