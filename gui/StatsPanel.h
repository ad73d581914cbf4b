// The statistics panel: the current frame and pass, frame time, preview latency, rays per
// second, a row per rank (threads, tiles, busy time, rays, stale tiles dropped) and the
// speedup/efficiency chart. The chart shows a loaded speedup CSV (one point per process count,
// with the ideal line) and this run's own point: Σ busy thread-seconds / wall time of the last
// full pass, over its render threads. With photon mapping: photons/s, the photons stored, the
// map's size, the photon pass's trace/build/send times and the gather radius.
#pragma once

#include <QWidget>
#include <vector>

#include "gui/SpeedupCsv.h"
#include "master/live/LiveRenderer.h"

class QLabel;
class QTableWidget;

namespace QtCharts {
class QChart;
class QLineSeries;
class QScatterSeries;
class QValueAxis;
}  // namespace QtCharts

namespace prism {

class StatsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit StatsPanel(QWidget* parent = nullptr);

  void showStats(const LiveStats& stats);
  void setSpeedupTable(const std::vector<SpeedupPoint>& points, const QString& name);
  // The ray kernels' instruction set on every rank of the job ("x86-64-v4"), shown with the
  // statistics.
  void setInstructionSet(const QString& name) { instructionSet_ = name; }

  // For tests: the per-rank table and the chart's series.
  const QTableWidget* rankTable() const { return table_; }
  const QtCharts::QLineSeries* csvSpeedup() const { return csvSpeedup_; }
  const QtCharts::QLineSeries* csvEfficiency() const { return csvEfficiency_; }
  const QtCharts::QScatterSeries* liveSpeedup() const { return liveSpeedup_; }
  QString summaryText() const;

 private:
  void rescaleAxes();

  QLabel* summary_;
  QTableWidget* table_;
  QtCharts::QChart* chart_;
  QtCharts::QLineSeries* ideal_;
  QtCharts::QLineSeries* csvSpeedup_;
  QtCharts::QLineSeries* csvEfficiency_;
  QtCharts::QScatterSeries* liveSpeedup_;
  QtCharts::QScatterSeries* liveEfficiency_;
  QtCharts::QValueAxis* axisP_;
  QtCharts::QValueAxis* axisSpeedup_;
  QtCharts::QValueAxis* axisEfficiency_;
  int maxP_ = 2;
  double maxSpeedup_ = 2.0;
  QString instructionSet_;
};

}  // namespace prism
