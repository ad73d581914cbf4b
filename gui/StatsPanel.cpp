#include "gui/StatsPanel.h"

#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>
#include <QtCharts/QChart>
#include <QtCharts/QChartView>
#include <QtCharts/QLineSeries>
#include <QtCharts/QScatterSeries>
#include <QtCharts/QValueAxis>
#include <algorithm>
#include <cmath>

#include "gui/FrameView.h"
#include "master/frame/ResourceCheck.h"

using namespace QtCharts;

namespace prism {
namespace {

QString siRate(double perSecond) {
  if (perSecond >= 1e6) return QString::number(perSecond / 1e6, 'f', 2) + " M";
  if (perSecond >= 1e3) return QString::number(perSecond / 1e3, 'f', 1) + " k";
  return QString::number(perSecond, 'f', 0) + " ";
}

QString milliseconds(double seconds) {
  return seconds > 0.0 ? QString::number(seconds * 1e3, 'f', 1) + " ms" : QString("—");
}

// The caustic-map line of the summary.
QString causticMapLines(const PhotonLiveStats& p) {
  if (p.noCasters) return "\ncaustic map  none: no light reaches a caustic caster";
  if (p.mapResolution == 0) return "\ncaustic map  building";
  // (No "²" after a placeholder: QString::arg reads a superscript digit as part of it.)
  // Two lines: as one it was the summary's widest, wider than the panel on a 1280-pixel screen.
  return QString("\ncaustic map  %1x%1 x %2 view(s), blur %3\n             built in %4 on rank 0")
      .arg(p.mapResolution)
      .arg(p.mapViews)
      .arg(p.mapBlur ? "on" : "off")
      .arg(milliseconds(p.mapBuildSeconds));
}

// The caustics lines of the summary: empty without caustics.
QString photonLines(const PhotonLiveStats& p) {
  if (p.method == CausticMethod::CausticMap) return causticMapLines(p);
  if (p.method != CausticMethod::PhotonMap) return {};
  if (p.noCasters) return "\nphotons      none: no light reaches a caustic caster";
  if (p.passes == 0) return "\nphotons      waiting for the first full pass";
  const PhotonPassStats& last = p.last;
  return QString("\nphotons/s    %1photons/s (%2 per pass)\n")
             .arg(siRate(last.photonsPerSecond()))
             .arg(p.photonsPerPass) +
         QString("stored       %1 photons, map %2\n")
             .arg(last.trace.stored)
             .arg(QString::fromStdString(formatBytes(static_cast<double>(last.mapBytes)))) +
         QString("passes       %1 of this view\n").arg(p.passes) +
         QString("photon pass  trace %1, kd-tree %2, %3\n")
             .arg(milliseconds(last.traceSeconds))
             .arg(milliseconds(last.buildSeconds))
             .arg(p.reused ? QString("the first view's, reused")
                           : "send " + milliseconds(last.distributeSeconds)) +
         QString("radii        %1 (each rank a share)\n").arg(milliseconds(last.radiiSeconds)) +
         QString("gather r     %1 (progressive)").arg(p.radius, 0, 'g', 4);
}

}  // namespace

StatsPanel::StatsPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  summary_ = new QLabel(this);
  summary_->setTextFormat(Qt::PlainText);
  summary_->setFont(QFont("Monospace", 9));
  layout->addWidget(summary_);

  table_ = new QTableWidget(0, 6, this);
  table_->setHorizontalHeaderLabels({"rank", "threads", "tiles", "busy s", "M rays", "stale"});
  table_->verticalHeader()->hide();
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setMinimumHeight(120);
  table_->setMaximumHeight(170);
  layout->addWidget(table_);

  chart_ = new QChart();
  chart_->setTitle("Speedup and efficiency");
  chart_->legend()->setAlignment(Qt::AlignBottom);
  ideal_ = new QLineSeries();
  ideal_->setName("ideal");
  ideal_->setPen(QPen(Qt::gray, 1, Qt::DashLine));
  csvSpeedup_ = new QLineSeries();
  csvSpeedup_->setName("speedup (CSV)");
  csvSpeedup_->setPointsVisible(true);
  csvEfficiency_ = new QLineSeries();
  csvEfficiency_->setName("efficiency (CSV)");
  csvEfficiency_->setPointsVisible(true);
  liveSpeedup_ = new QScatterSeries();
  liveSpeedup_->setName("this run: speedup");
  liveSpeedup_->setMarkerSize(11);
  liveEfficiency_ = new QScatterSeries();
  liveEfficiency_->setName("this run: efficiency");
  liveEfficiency_->setMarkerShape(QScatterSeries::MarkerShapeRectangle);
  liveEfficiency_->setMarkerSize(9);
  for (QAbstractSeries* s : std::initializer_list<QAbstractSeries*>{
           ideal_, csvSpeedup_, csvEfficiency_, liveSpeedup_, liveEfficiency_}) {
    chart_->addSeries(s);
  }
  axisP_ = new QValueAxis();
  axisP_->setTitleText("processes / threads p");
  axisP_->setLabelFormat("%d");
  axisSpeedup_ = new QValueAxis();
  axisSpeedup_->setTitleText("speedup");
  axisEfficiency_ = new QValueAxis();
  axisEfficiency_->setTitleText("efficiency");
  axisEfficiency_->setRange(0.0, 1.2);
  chart_->addAxis(axisP_, Qt::AlignBottom);
  chart_->addAxis(axisSpeedup_, Qt::AlignLeft);
  chart_->addAxis(axisEfficiency_, Qt::AlignRight);
  for (QAbstractSeries* s :
       std::initializer_list<QAbstractSeries*>{ideal_, csvSpeedup_, liveSpeedup_}) {
    s->attachAxis(axisP_);
    s->attachAxis(axisSpeedup_);
  }
  for (QAbstractSeries* s :
       std::initializer_list<QAbstractSeries*>{csvEfficiency_, liveEfficiency_}) {
    s->attachAxis(axisP_);
    s->attachAxis(axisEfficiency_);
  }
  auto* view = new QChartView(chart_, this);
  view->setRenderHint(QPainter::Antialiasing);
  view->setMinimumHeight(330);
  layout->addWidget(view, 1);
  rescaleAxes();
  summary_->setText("waiting for the first tiles");
}

QString StatsPanel::summaryText() const {
  return summary_->text();
}

void StatsPanel::rescaleAxes() {
  ideal_->clear();
  for (int p = 1; p <= maxP_; ++p) ideal_->append(p, p);
  axisP_->setRange(1, maxP_);
  axisP_->setTickCount(std::min(maxP_, 9));
  axisSpeedup_->setRange(0.0, std::ceil(std::max<double>(maxSpeedup_, maxP_) * 1.1));
}

void StatsPanel::setSpeedupTable(const std::vector<SpeedupPoint>& points, const QString& name) {
  csvSpeedup_->clear();
  csvEfficiency_->clear();
  for (const SpeedupPoint& p : points) {
    csvSpeedup_->append(p.processes, p.speedup);
    csvEfficiency_->append(p.processes, p.efficiency);
    maxP_ = std::max(maxP_, p.processes);
    maxSpeedup_ = std::max(maxSpeedup_, p.speedup);
  }
  chart_->setTitle("Speedup and efficiency — " + name);
  rescaleAxes();
}

void StatsPanel::showStats(const LiveStats& s) {
  table_->setRowCount(static_cast<int>(s.ranks.size()));
  auto set = [this](int row, int column, const QString& text) {
    auto* item = table_->item(row, column);
    if (!item) {
      item = new QTableWidgetItem();
      item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      table_->setItem(row, column, item);
    }
    item->setText(text);
  };
  for (size_t i = 0; i < s.ranks.size(); ++i) {
    const RankStats& r = s.ranks[i];
    const int row = static_cast<int>(i);
    set(row, 0, QString::number(r.rank) + (r.retired ? " (retired)" : ""));
    table_->item(row, 0)->setForeground(FrameView::rankColor(r.rank).darker(130));
    set(row, 1, QString::number(r.threads));
    set(row, 2, QString::number(r.tiles));
    set(row, 3, QString::number(r.busySeconds, 'f', 2));
    set(row, 4, QString::number(static_cast<double>(r.rays.total()) / 1e6, 'f', 2));
    set(row, 5, QString::number(r.staleTiles));
  }
  const double speedup = s.lastPassSeconds > 0.0 ? s.lastPassBusySeconds / s.lastPassSeconds : 0.0;
  const double efficiency = s.totalThreads > 0 ? speedup / s.totalThreads : 0.0;
  summary_->setText(
      QString("frame %1   view %2   pass %3 (%4 full done)\n")
          .arg(s.frame)
          .arg(s.viewId)
          .arg(s.pass)
          .arg(s.passesDone) +
      QString("rays/s       %1rays/s\n").arg(siRate(s.raysPerSecond)) +
      (instructionSet_.isEmpty() ? QString() : QString("kernels      %1\n").arg(instructionSet_)) +
      QString("frame time   %1 median, %2 p95\n")
          .arg(milliseconds(s.frameTimes.medianSeconds))
          .arg(milliseconds(s.frameTimes.p95Seconds)) +
      QString("target       %1 a frame\n").arg(milliseconds(s.frameTimeTargetSeconds)) +
      QString("frames/s     %1 at %2x%3\n")
          .arg(s.frameTimes.framesPerSecond, 0, 'f', 1)
          .arg(s.frameTimes.shownWidth)
          .arg(s.frameTimes.shownHeight) +
      QString("moving       %1 frames at full resolution, %2 reduced\n")
          .arg(s.frameTimes.fullResolutionFrames)
          .arg(s.frameTimes.reducedFrames) +
      QString("full pass    %1   (Σ busy %2 thread-s)\n")
          .arg(milliseconds(s.lastPassSeconds))
          .arg(s.lastPassBusySeconds, 0, 'f', 2) +
      QString("first frame  %1 after the move\n").arg(milliseconds(s.previewLatencySeconds)) +
      QString("first full   %1 after the move\n").arg(milliseconds(s.firstFullSeconds)) +
      QString("speedup      %1 on %2 threads, efficiency %3")
          .arg(speedup, 0, 'f', 2)
          .arg(s.totalThreads)
          .arg(efficiency, 0, 'f', 2) +
      photonLines(s.photons));
  if (speedup > 0.0 && s.totalThreads > 0) {
    liveSpeedup_->replace(QList<QPointF>{QPointF(s.totalThreads, speedup)});
    liveEfficiency_->replace(QList<QPointF>{QPointF(s.totalThreads, efficiency)});
    if (s.totalThreads > maxP_ || speedup > maxSpeedup_) {
      maxP_ = std::max(maxP_, s.totalThreads);
      maxSpeedup_ = std::max(maxSpeedup_, speedup);
      rescaleAxes();
    }
  }
}

}  // namespace prism
