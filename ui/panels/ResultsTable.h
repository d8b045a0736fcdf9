#pragma once
/// @file ResultsTable.h
/// The detections of the last recognition: score, position, orientation (roll, pitch, yaw),
/// cluster, grip points and, with several views of the part, the view that found it; one row per
/// detection, best first. Each row's header is its ID (1, 2, …) beside a swatch of the colour the
/// viewport draws that detection in, labelled with the same ID. Selecting a row highlights that
/// detection.

#include "core/common/Detection.h"

#include <QStringList>
#include <QTableWidget>
#include <vector>

namespace scanpick::ui {

class ResultsTable : public QTableWidget {
  Q_OBJECT
public:
  explicit ResultsTable(QWidget* parent = nullptr);
  /// Shows `detections` (row i = detection i). `view_names` names the views of the part
  /// (Detection::model_index); the View column is shown only when it names several.
  void setDetections(const std::vector<core::Detection>& detections, const QStringList& view_names);

signals:
  /// Row selected (-1 when the selection was cleared).
  void detectionSelected(int row);

protected:
  /// Headers and rows follow a language switch.
  void changeEvent(QEvent* event) override;

private:
  void setHeaderTexts();

  std::vector<core::Detection> m_detections;
  QStringList m_view_names;
};

} // namespace scanpick::ui
