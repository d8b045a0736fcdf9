#include "ui/panels/CoveragePanel.h"

#include "ui/jobs/JobRunner.h"
#include "ui/panels/CoverageSphere.h"

#include <QEvent>
#include <QLabel>
#include <QScrollArea>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanpick::ui {
namespace {

QLabel* wrappedLabel(const char* name, QWidget* parent) {
  auto* label = new QLabel(parent);
  label->setObjectName(QString::fromLatin1(name));
  label->setWordWrap(true);
  label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  return label;
}

/// What the background job measures for the views.
struct CoverageReport {
  core::ViewCoverage coverage;
  std::vector<core::ViewAmbiguities> ambiguities; ///< per view
};

/// A coloured square for the legend (rich text).
QString swatch(const QColor& colour) {
  return QStringLiteral("<span style=\"color:%1\">&#9632;</span>").arg(colour.name());
}

} // namespace

CoveragePanel::CoveragePanel(JobPool* pool, QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("coveragePanel"));
  m_jobs = new JobRunner(pool, this);
  m_sphere = new CoverageSphere(this);
  m_summary = wrappedLabel("coverageSummary", this);
  m_legend = wrappedLabel("coverageLegend", this);
  m_legend->setTextFormat(Qt::RichText);
  m_suggestions = wrappedLabel("coverageSuggestions", this);
  m_ambiguity_text = wrappedLabel("coverageAmbiguities", this);
  m_ambiguity_text->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(m_summary);
  layout->addWidget(m_sphere, 3);
  layout->addWidget(m_legend);
  layout->addWidget(m_suggestions);
  // Several sentences per view: they scroll rather than squeeze the sphere.
  m_ambiguity_scroll = new QScrollArea(this);
  m_ambiguity_scroll->setWidget(m_ambiguity_text);
  m_ambiguity_scroll->setWidgetResizable(true);
  m_ambiguity_scroll->setFrameShape(QFrame::NoFrame);
  layout->addWidget(m_ambiguity_scroll, 1);
  m_texts.bind(this, [this] { showTexts(); });
}

void CoveragePanel::setViews(std::vector<std::shared_ptr<const core::TaughtModel>> views) {
  m_coverage.reset();
  m_ambiguities.clear();
  m_sphere->clear();
  if (views.empty()) {
    m_jobs->cancel();
    m_state = State::NoModel;
    showTexts();
    emit coverageShown();
    return;
  }
  m_state = State::Measuring;
  showTexts();
  const core::ViewCoverageOptions options = m_options;
  m_jobs->run<CoverageReport>(
      [views = std::move(views), options](const core::ProgressFn&) {
        CoverageReport report{core::viewCoverage(views, options), {}};
        for (const auto& view : views)
          report.ambiguities.push_back(core::analyzeViewAmbiguities(view, view->params));
        return report;
      },
      [this](std::shared_ptr<const CoverageReport> report) {
        m_coverage = std::make_shared<const core::ViewCoverage>(report->coverage);
        m_ambiguities = report->ambiguities;
        m_state = State::Shown;
        m_sphere->setCoverage(*m_coverage, m_options.tolerance_deg);
        showTexts();
        emit coverageShown();
      },
      [this](const QString& error) {
        m_error = error;
        m_state = State::Failed;
        showTexts();
        emit coverageShown();
      });
}

void CoveragePanel::cancel() {
  m_jobs->cancel();
}

QString CoveragePanel::summaryText() const {
  return m_summary->text();
}

QString CoveragePanel::suggestionsText() const {
  return m_suggestions->text();
}

QString CoveragePanel::ambiguitiesText() const {
  return m_ambiguity_text->text();
}

QString CoveragePanel::describeDirection(const Eigen::Vector3d& d_part) {
  const Eigen::Vector3d d = d_part.normalized();
  const double elevation = std::asin(std::clamp(d.z(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  double azimuth = std::atan2(d.y(), d.x()) * 180.0 / std::numbers::pi;
  if (azimuth < 0)
    azimuth += 360.0;
  // Rounded as shown, so that 359.6° reads 0°.
  const int azimuth_deg = int(std::lround(azimuth)) % 360;
  const int elevation_deg = int(std::lround(elevation));
  // Straight above or below the azimuth means nothing.
  if (elevation_deg == 90)
    return tr("from straight above (+Z)");
  if (elevation_deg == -90)
    return tr("from straight below (−Z)");
  if (elevation_deg >= 60)
    return tr("from above (elevation %1°, azimuth %2°)").arg(elevation_deg).arg(azimuth_deg);
  if (elevation_deg <= -60)
    return tr("from below (elevation %1°, azimuth %2°)").arg(elevation_deg).arg(azimuth_deg);
  return tr("from the side at azimuth %1° (elevation %2°)").arg(azimuth_deg).arg(elevation_deg);
}

void CoveragePanel::showTexts() {
  m_sphere->setVisible(m_state == State::Shown);
  m_legend->setVisible(m_state == State::Shown);
  m_suggestions->setVisible(m_state == State::Shown);
  m_ambiguity_scroll->setVisible(m_state == State::Shown);
  m_ambiguity_text->clear();
  m_summary->setToolTip(QString());
  switch (m_state) {
  case State::NoModel:
    m_summary->setText(tr("No model: open one (File → Open scan or model…) or teach one to see "
                          "which viewing directions its views cover."));
    return;
  case State::Measuring:
    m_summary->setText(tr("Measuring the view coverage…"));
    return;
  case State::Failed:
    m_summary->setText(tr("The view coverage could not be measured: %1").arg(m_error));
    return;
  case State::Shown:
    break;
  }
  const core::ViewCoverage& c = *m_coverage;
  const QString percent = QString::number(100.0 * c.covered, 'f', 0);
  m_summary->setText(tr("%n view(s) placed (%1 left out): %2 % of the viewing directions covered",
                        "", int(c.view_directions_part.size()))
                         .arg(c.unplaced)
                         .arg(percent));
  m_summary->setToolTip(
      tr("A direction is covered when it lies within %1° of a taught view's own viewing "
         "direction. Views left out do not know their place in the part (teach them with the "
         "part's pose) and are not counted.")
          .arg(m_options.tolerance_deg, 0, 'f', 0));
  m_legend->setText(QStringLiteral("%1 %2 &nbsp; %3 %4 &nbsp; %5 %6 &nbsp; %7 %8")
                        .arg(swatch(CoverageSphere::coveredColour()), tr("covered"),
                             swatch(CoverageSphere::uncoveredColour()), tr("not covered"),
                             swatch(CoverageSphere::viewColour()), tr("taught view"),
                             QStringLiteral("&#9312;"), tr("suggested view")));
  showAmbiguities();
  if (c.missing_part.empty()) {
    m_suggestions->setText(tr("Every viewing direction is covered."));
    m_suggestions->setToolTip(QString());
    return;
  }
  QStringList lines{tr("To cover more, teach the part seen:")};
  for (std::size_t i = 0; i < c.missing_part.size(); ++i) {
    const Eigen::Vector3d& d = c.missing_part[i];
    lines << tr("%1. %2: direction (%3, %4, %5) in the part frame")
                 .arg(i + 1)
                 .arg(describeDirection(d))
                 .arg(d.x(), 0, 'f', 2)
                 .arg(d.y(), 0, 'f', 2)
                 .arg(d.z(), 0, 'f', 2);
  }
  m_suggestions->setText(lines.join('\n'));
  m_suggestions->setToolTip(
      tr("Directions from the part towards the camera, in the part frame: azimuth in the XY "
         "plane from +X towards +Y, elevation from the XY plane towards +Z."));
}

void CoveragePanel::showAmbiguities() {
  QStringList lines{tr("What a scan of each view may leave open:")};
  for (std::size_t v = 0; v < m_ambiguities.size(); ++v)
    for (const std::string& line : core::describeAmbiguities(m_ambiguities[v]))
      lines << tr("View %1: %2").arg(v + 1).arg(QString::fromStdString(line));
  m_ambiguity_text->setText(lines.join('\n'));
  m_ambiguity_text->setToolTip(
      tr("Rotations a view's own surface cannot pin (an axis of revolution, a near symmetry). A "
         "detection reports them as its free turn axis or its alternative poses wherever the scan "
         "does not tell them apart."));
}

void CoveragePanel::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange)
    m_texts.apply();
  QWidget::changeEvent(event);
}

} // namespace scanpick::ui
