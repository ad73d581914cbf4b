#include "gui/ChartImage.h"

#include <QApplication>
#include <QFile>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QVBoxLayout>
#include <QWidget>
#include <QtCharts/QChart>
#include <QtCharts/QChartView>
#include <QtCharts/QLineSeries>
#include <QtCharts/QLogValueAxis>
#include <QtCharts/QScatterSeries>
#include <QtCharts/QValueAxis>
#include <algorithm>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "image/ToneMap.h"

using namespace QtCharts;

namespace prism {
namespace {

// `prism speedup` runs without a Qt application; one is made on first use and kept. Without a
// display Qt would abort, so the offscreen platform is chosen first.
void ensureApplication() {
  if (QApplication::instance()) return;
  const bool display = std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
  if (!display && !std::getenv("QT_QPA_PLATFORM")) ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  static int argc = 1;
  static char name[] = "prism";
  static char* argv[] = {name, nullptr};
  static std::unique_ptr<QApplication> app = std::make_unique<QApplication>(argc, argv);
}

// The offscreen platform's chatter (no window manager hints, no runtime folder) says nothing
// about the chart; everything else still reaches stderr.
QtMessageHandler defaultHandler = nullptr;
void quietOffscreenNotes(QtMsgType type, const QMessageLogContext& context, const QString& text) {
  if (text.contains("propagateSizeHints") || text.contains("XDG_RUNTIME_DIR")) return;
  if (defaultHandler) defaultHandler(type, context, text);
}

// Distinct, print-friendly colours for the measured and modelled series, in order.
QColor seriesColour(size_t index) {
  static const QColor colours[] = {QColor(31, 119, 180),  QColor(214, 39, 40),  QColor(44, 160, 44),
                                   QColor(148, 103, 189), QColor(255, 127, 14), QColor(140, 86, 75),
                                   QColor(23, 190, 207),  QColor(188, 189, 34)};
  return colours[index % (sizeof colours / sizeof colours[0])];
}

QAbstractAxis* makeAxis(bool log, double base, const QString& title, double low, double high) {
  if (log) {
    auto* axis = new QLogValueAxis;
    axis->setBase(base);
    if (base == 10.0) axis->setMinorTickCount(8);  // grid lines at 2..9 of every decade
    axis->setLabelFormat("%g");
    axis->setRange(low, high);
    axis->setTitleText(title);
    return axis;
  }
  auto* axis = new QValueAxis;
  axis->setRange(low, high);
  axis->setTitleText(title);
  axis->applyNiceNumbers();
  return axis;
}

QChartView* drawPanel(const ChartPanel& panel) {
  auto* chart = new QChart;
  chart->setTitle(QString::fromStdString(panel.title));
  chart->setAnimationOptions(QChart::NoAnimation);
  chart->legend()->setAlignment(Qt::AlignRight);
  double xLow = 1e300, xHigh = -1e300, yLow = 1e300, yHigh = -1e300;
  std::vector<QAbstractSeries*> all;
  auto* marked = new QScatterSeries;
  marked->setName(QString::fromStdString(panel.markedName));
  marked->setMarkerShape(QScatterSeries::MarkerShapeRectangle);
  marked->setMarkerSize(13);
  marked->setColor(Qt::transparent);
  marked->setBorderColor(Qt::black);
  size_t colour = 0;
  // A front goes first, so the curves are drawn over it.
  std::vector<const ChartSeries*> ordered;
  for (const ChartSeries& s : panel.series)
    if (s.kind == ChartSeries::Kind::Front) ordered.push_back(&s);
  for (const ChartSeries& s : panel.series)
    if (s.kind != ChartSeries::Kind::Front) ordered.push_back(&s);
  for (const ChartSeries* series : ordered) {
    const ChartSeries& s = *series;
    auto* line = new QLineSeries;
    line->setName(QString::fromStdString(s.name));
    QPen pen;
    switch (s.kind) {
      case ChartSeries::Kind::Measured:
        pen = QPen(seriesColour(colour++), 2.5);
        break;
      case ChartSeries::Kind::Model:
        pen = QPen(seriesColour(colour++), 1.8, Qt::DashLine);
        break;
      case ChartSeries::Kind::Ideal:
        pen = QPen(QColor(120, 120, 120), 1.8, Qt::DashLine);
        break;
      case ChartSeries::Kind::Front:
        pen = QPen(QColor(0, 0, 0, 70), 11.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin);
        break;
    }
    line->setPen(pen);
    line->setPointsVisible(s.kind == ChartSeries::Kind::Measured);
    for (size_t i = 0; i < s.x.size(); ++i) {
      line->append(s.x[i], s.y[i]);
      xLow = std::min(xLow, s.x[i]);
      xHigh = std::max(xHigh, s.x[i]);
      yLow = std::min(yLow, s.y[i]);
      yHigh = std::max(yHigh, s.y[i]);
      if (i < s.marked.size() && s.marked[i]) marked->append(s.x[i], s.y[i]);
    }
    all.push_back(line);
  }
  if (marked->count() > 0) {
    all.push_back(marked);
  } else {
    delete marked;
  }
  for (QAbstractSeries* s : all) chart->addSeries(s);
  if (xLow > xHigh) xLow = 0.0, xHigh = 1.0, yLow = 0.0, yHigh = 1.0;
  if (panel.logX) {
    xLow = std::max(xLow, 1e-9) / 1.3;
    xHigh *= 1.3;
  } else {
    xLow = std::min(0.0, xLow);
    xHigh += 0.5;
  }
  if (panel.logY) {
    yLow = std::max(yLow, 1e-9) / 1.5;
    yHigh *= 1.5;
  } else {
    yLow = std::min(0.0, yLow);
    yHigh = yHigh * 1.1 + 1e-9;
  }
  QAbstractAxis* x =
      makeAxis(panel.logX, panel.logBase, QString::fromStdString(panel.xTitle), xLow, xHigh);
  QAbstractAxis* y =
      makeAxis(panel.logY, panel.logBase, QString::fromStdString(panel.yTitle), yLow, yHigh);
  chart->addAxis(x, Qt::AlignBottom);
  chart->addAxis(y, Qt::AlignLeft);
  for (QAbstractSeries* s : all) {
    s->attachAxis(x);
    s->attachAxis(y);
  }
  auto* view = new QChartView(chart);
  view->setRenderHint(QPainter::Antialiasing);
  return view;
}

// A strip's thumbnails side by side, each with its caption under it.
QWidget* drawStrip(const ThumbnailStrip& strip) {
  auto* box = new QWidget;
  auto* column = new QVBoxLayout(box);
  auto* title = new QLabel(QString::fromStdString(strip.title));
  QFont font = title->font();
  font.setBold(true);
  title->setFont(font);
  column->addWidget(title);
  auto* row = new QHBoxLayout;
  const DisplayEncoder encode(strip.exposure);
  for (const Thumbnail& t : strip.thumbnails) {
    QImage picture(t.image.width, t.image.height, QImage::Format_RGB888);
    for (int y = 0; y < t.image.height; ++y) {
      uchar* line = picture.scanLine(y);
      for (int x = 0; x < t.image.width; ++x) {
        const Color& c = t.image.at(x, y);
        line[3 * x] = encode(c.x);
        line[3 * x + 1] = encode(c.y);
        line[3 * x + 2] = encode(c.z);
      }
    }
    auto* cell = new QVBoxLayout;
    auto* image = new QLabel;
    image->setPixmap(QPixmap::fromImage(picture));
    cell->addWidget(image);
    auto* caption = new QLabel(QString::fromStdString(t.caption));
    QFont small = caption->font();
    small.setPointSizeF(small.pointSizeF() * 0.85);
    caption->setFont(small);
    caption->setWordWrap(true);
    caption->setMaximumWidth(std::max(t.image.width, 110));
    cell->addWidget(caption);
    cell->addStretch();
    row->addLayout(cell);
  }
  row->addStretch();
  column->addLayout(row);
  return box;
}

}  // namespace

void writeChartImage(const Chart& chart, const std::string& pngPath) {
  defaultHandler = qInstallMessageHandler(quietOffscreenNotes);
  struct Restore {
    ~Restore() { qInstallMessageHandler(defaultHandler); }
  } restore;
  ensureApplication();
  QWidget page;
  page.setAttribute(Qt::WA_DontShowOnScreen);
  page.setStyleSheet("background: white;");
  auto* layout = new QVBoxLayout(&page);
  auto* title = new QLabel(QString::fromStdString(chart.title));
  QFont font = title->font();
  font.setPointSize(font.pointSize() + 3);
  font.setBold(true);
  title->setFont(font);
  layout->addWidget(title);
  auto* note = new QLabel(QString::fromStdString(chart.note));
  note->setWordWrap(true);
  layout->addWidget(note);
  auto* row = new QHBoxLayout;
  for (const ChartPanel& panel : chart.panels) row->addWidget(drawPanel(panel));
  layout->addLayout(row, 1);
  // Strips two to a row under the panels; each row adds its thumbnails, titles and captions.
  auto* strips = new QGridLayout;
  int height = 640;
  for (size_t i = 0; i < chart.strips.size(); ++i) {
    strips->addWidget(drawStrip(chart.strips[i]), static_cast<int>(i / 2), static_cast<int>(i % 2));
    if (i % 2 == 0) {
      int tallest = 0;
      for (size_t j = i; j < std::min(i + 2, chart.strips.size()); ++j)
        for (const Thumbnail& t : chart.strips[j].thumbnails)
          tallest = std::max(tallest, t.image.height);
      height += tallest + 110;
    }
  }
  layout->addLayout(strips);
  page.resize(1000 * static_cast<int>(std::max<size_t>(chart.panels.size(), 1)), height);
  page.show();
  QApplication::processEvents();
  const QPixmap image = page.grab();
  page.hide();
  const QString temporary = QString::fromStdString(pngPath + ".tmp.png");
  if (image.isNull() || !image.save(temporary, "PNG")) {
    throw std::runtime_error("cannot write the chart " + pngPath);
  }
  QFile::remove(QString::fromStdString(pngPath));
  if (!QFile::rename(temporary, QString::fromStdString(pngPath))) {
    throw std::runtime_error("cannot write the chart " + pngPath);
  }
}

}  // namespace prism
