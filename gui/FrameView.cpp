#include "gui/FrameView.h"

#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include "gui/HelpText.h"

namespace prism {

FrameView::FrameView(const FrameAccumulator& frame, float exposure, QWidget* parent)
    : QWidget(parent),
      frame_(frame),
      encoder_(exposure),
      display_(frame.image().width, frame.image().height, QImage::Format_RGB888) {
  display_.fill(Qt::black);
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(160, 90);
  connect(&timer_, &QTimer::timeout, this, &FrameView::refresh);
  timer_.start(16);
}

QSize FrameView::sizeHint() const {
  return display_.size();
}

QColor FrameView::rankColor(int rank) {
  return QColor::fromHsv((rank * 137 + 30) % 360, 230, 255);  // golden-angle hues
}

void FrameView::setShowTiles(bool show) {
  showTiles_ = show;
  update();
}

void FrameView::setShowHelp(bool show) {
  showHelp_ = show;
  update();
}

void FrameView::convert(const TileRect& r) {
  const ImageRgb& image = frame_.image();
  for (int y = r.y; y < r.y + r.height; ++y) {
    uchar* line = display_.scanLine(y);
    for (int x = r.x; x < r.x + r.width; ++x) {
      const Color& c = image.at(x, y);
      line[3 * x + 0] = encoder_(c.r);
      line[3 * x + 1] = encoder_(c.g);
      line[3 * x + 2] = encoder_(c.b);
    }
  }
}

void FrameView::refresh() {
  if (!changed_) return;
  changed_ = false;
  // The accumulator belongs to the main thread, like this widget: no lock needed.
  const TileRect dirty = const_cast<FrameAccumulator&>(frame_).takeDirty();
  if (dirty.width > 0) convert(dirty);
  update();
}

QRect FrameView::imageRect() const {
  const QSize scaled = display_.size().scaled(size(), Qt::KeepAspectRatio);
  return QRect(QPoint((width() - scaled.width()) / 2, (height() - scaled.height()) / 2), scaled);
}

void FrameView::setOverlay(const QImage& image, const QString& caption) {
  overlay_ = image;
  overlayCaption_ = caption;
  overlayShown_ = true;
  update();
}

void FrameView::clearOverlay() {
  if (!overlayShown_) return;
  overlayShown_ = false;
  overlay_ = QImage();
  overlayCaption_.clear();
  update();
}

void FrameView::paintOverlay(QPainter& painter) {
  if (!overlay_.isNull()) {
    const QSize scaled = overlay_.size().scaled(size(), Qt::KeepAspectRatio);
    const QRect target(QPoint((width() - scaled.width()) / 2, (height() - scaled.height()) / 2),
                       scaled);
    painter.drawImage(target, overlay_);  // no smoothing: each texel stays a square
  }
  painter.setPen(Qt::white);
  painter.fillRect(QRect(0, 0, width(), 28), QColor(0, 0, 0, 170));
  painter.drawText(QRect(8, 0, width() - 16, 28), Qt::AlignLeft | Qt::AlignVCenter,
                   overlayCaption_);
}

void FrameView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), Qt::black);
  if (overlayShown_) {
    paintOverlay(painter);
    if (showHelp_) paintHelp(painter);
    emit painted(frame_.pass().viewId, frame_.completedPass());
    return;
  }
  const QRect target = imageRect();
  painter.drawImage(target, display_);
  if (showTiles_) {
    const double sx = static_cast<double>(target.width()) / display_.width();
    const double sy = static_cast<double>(target.height()) / display_.height();
    for (const FrameAccumulator::InFlight& t : frame_.inFlight()) {
      painter.setPen(QPen(rankColor(t.rank), 2));
      painter.drawRect(QRectF(target.x() + t.rect.x * sx + 1, target.y() + t.rect.y * sy + 1,
                              t.rect.width * sx - 2, t.rect.height * sy - 2));
    }
  }
  if (showHelp_) paintHelp(painter);
  emit painted(frame_.pass().viewId, frame_.completedPass());
}

void FrameView::paintHelp(QPainter& painter) {
  painter.fillRect(rect(), QColor(0, 0, 0, 170));
  painter.setPen(Qt::white);
  QFont font("Monospace");
  font.setStyleHint(QFont::TypeWriter);
  painter.setFont(font);
  painter.drawText(rect().adjusted(24, 24, -24, -24), Qt::AlignLeft | Qt::AlignTop,
                   QString::fromUtf8(kViewerHelpText));
}

void FrameView::mousePressEvent(QMouseEvent* event) {
  lastMouse_ = event->pos();
}

void FrameView::mouseMoveEvent(QMouseEvent* event) {
  if (!(event->buttons() & Qt::LeftButton)) return;
  const QPoint delta = event->pos() - lastMouse_;
  lastMouse_ = event->pos();
  if (!delta.isNull()) emit dragged(delta.x(), delta.y());
}

void FrameView::wheelEvent(QWheelEvent* event) {
  const int steps = event->angleDelta().y() / 120;
  if (steps != 0) emit wheelTurned(steps);
}

}  // namespace prism
