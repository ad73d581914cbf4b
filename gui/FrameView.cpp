#include "gui/FrameView.h"

#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include "gui/HelpText.h"

namespace prism {

FrameView::FrameView(const DisplayFrame& frame, QWidget* parent)
    : QWidget(parent),
      frame_(frame),
      // The frame's bytes, not a copy: their buffer keeps its size and place for the frame's life.
      display_(frame.bytes().data(), frame.width(), frame.height(), frame.width() * 3,
               QImage::Format_RGB888) {
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

void FrameView::refresh() {
  if (!changed_) return;
  changed_ = false;
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
    emit painted(frame_.pass().viewId, frame_.state().completedPass);
    return;
  }
  const QRect target = imageRect();
  painter.drawImage(target, display_);
  if (showTiles_) {
    const double sx = static_cast<double>(target.width()) / display_.width();
    const double sy = static_cast<double>(target.height()) / display_.height();
    for (const DisplayTile& t : frame_.state().inFlight) {
      painter.setPen(QPen(rankColor(t.rank), 2));
      painter.drawRect(QRectF(target.x() + t.rect.x * sx + 1, target.y() + t.rect.y * sy + 1,
                              t.rect.width * sx - 2, t.rect.height * sy - 2));
    }
  }
  if (showHelp_) paintHelp(painter);
  emit painted(frame_.pass().viewId, frame_.state().completedPass);
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
