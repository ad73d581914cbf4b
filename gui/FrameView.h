// The live image: the display bytes of the window's DisplayFrame, repainted on a timer (60 Hz
// at most, and only when something changed), so a burst of news costs one repaint. Draws the tiles
// in flight outlined in their rank's colour (toggleable) and the help overlay. A light-space debug
// image (the caustic maps of R, P, C) can be shown instead of the frame, which keeps rendering
// underneath.
#pragma once

#include <QImage>
#include <QTimer>
#include <QWidget>

#include "master/live/DisplayFrame.h"

class QPainter;

namespace prism {

class FrameView : public QWidget {
  Q_OBJECT

 public:
  explicit FrameView(const DisplayFrame& frame, QWidget* parent = nullptr);

  void setShowTiles(bool show);
  bool showTiles() const { return showTiles_; }
  void setShowHelp(bool show);
  bool showHelp() const { return showHelp_; }
  // Shows `image` (any size, scaled to fit with its texels kept sharp) with a caption instead of
  // the frame; a null image shows the caption alone. clearOverlay() returns to the frame.
  void setOverlay(const QImage& image, const QString& caption);
  void clearOverlay();
  bool showsOverlay() const { return overlayShown_; }
  const QImage& overlayImage() const { return overlay_; }
  const QString& overlayCaption() const { return overlayCaption_; }
  // Something changed (a tile, an assignment, a new pass): repaint at the next tick.
  void markChanged() { changed_ = true; }

  // The image as displayed (sRGB bytes), at the frame's resolution.
  const QImage& displayImage() const { return display_; }
  // Where the image is drawn in the widget (aspect kept, centred).
  QRect imageRect() const;
  QSize sizeHint() const override;

  // A rank's outline colour: distinct hues, the same for a rank every time.
  static QColor rankColor(int rank);

 signals:
  // After a paint: the view it showed and the highest pass of it shown complete (-1: none).
  void painted(uint64_t viewId, int completedPass);
  void dragged(int dx, int dy);  // mouse drag, in pixels
  void wheelTurned(int steps);   // + away from the user

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  void refresh();
  void paintOverlay(QPainter& painter);
  void paintHelp(QPainter& painter);

  const DisplayFrame& frame_;
  QImage display_;
  QTimer timer_;
  bool changed_ = false;
  bool showTiles_ = true;
  bool showHelp_ = false;
  bool overlayShown_ = false;
  QImage overlay_;
  QString overlayCaption_;
  QPoint lastMouse_;
};

}  // namespace prism
