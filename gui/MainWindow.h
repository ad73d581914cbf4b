// The viewer window: the live frame in the middle, a side panel with the render controls and
// the statistics, menus for saving the image and loading a speedup table, and the keys listed
// in gui/HelpText.h. It drives a LiveSource (master/live/LiveSource.h): the renderer in this
// process, or a job over a connection, the same way. Every camera or setting change asks the
// source for a new view; the source's news (display bytes of what changed, the pass on show,
// statistics) is taken whenever the source wakes the window.
#pragma once

#include <QMainWindow>
#include <array>
#include <functional>
#include <future>
#include <optional>

#include "gui/CameraController.h"
#include "gui/LightSpaceImage.h"
#include "master/live/DisplayFrame.h"
#include "master/live/LiveSource.h"
#include "scene/CausticMethods.h"

class QSpinBox;
class QRadioButton;
class QVBoxLayout;
class QAction;
class QCheckBox;
class QLabel;
class QTimer;

namespace prism {

class FrameView;
class StatsPanel;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(LiveSource& source, QWidget* parent = nullptr);
  ~MainWindow() override;

  // Asks for the first view (the scene's camera), unless the source resumes one; call once the
  // source runs.
  void startRendering();

  // Sizes the window to `preferred` where the screen it opens on has room, else to the room
  // there is (on a 1280x800 screen the side panel stays on screen), and centres it there.
  // The frame keeps its aspect ratio inside whatever the view gets (FrameView::imageRect).
  void fitToScreen(const QSize& preferred);

  // Saves the current image: a PNG as the display bytes shown, any other format from the
  // source's full-precision image (EXR linear). Throws std::runtime_error.
  void saveImage(const QString& path);
  // Loads a speedup CSV into the chart; returns an error message, empty on success.
  QString loadSpeedupCsv(const QString& path);

  // Every view asked for from now on renders at most this many full passes
  // (--exit-after-passes: the image saved is exactly that many).
  void limitPasses(int passes) { settings_.maxPasses = passes; }
  // Every view asked for from now on asks the renderer for this frame-time target.
  void setFrameTime(double seconds) { settings_.frameTimeSeconds = seconds; }

  CameraController& cameraController() { return camera_; }
  // Sends the current camera and settings as a new view.
  void viewChanged();

  // The caustics switch and photon budget of the side panel; a change is a new view. Caustic
  // maps refused (refuseCausticMaps) leave the method as it was and say why in the status bar.
  void setCausticMethod(CausticMethod method);
  // Caustic maps cannot be built here (they would not fit in memory, LiveRenderer::
  // causticMapsRefusal): their switch and light-space views are disabled, with `why` on them.
  void refuseCausticMaps(const QString& why);
  void setPhotonsPerPass(uint64_t photons);
  // The caustic map's Gaussian blur (b); a change is a new view when caustic mapping is on.
  void setCausticMapBlur(bool blur);

  // Shows a light-space map instead of the frame (R, P, C), once the maps are built; the frame
  // keeps rendering underneath. Back with setDebugView (n, N).
  void showLightSpace(LightSpaceMap which);
  // The light-space map on show, if any (the overlay may still say the maps are being built).
  std::optional<LightSpaceMap> lightSpaceShown() const { return lightSpace_; }

  const ViewSettings& viewSettings() const { return settings_; }
  const DisplayFrame& frame() const { return frame_; }
  FrameView* frameView() const { return view_; }
  StatsPanel* statsPanel() const { return stats_; }
  int fullPassesDone() const { return fullPassesDone_; }
  uint64_t viewId() const { return frame_.pass().viewId; }
  // The tag of the latest view asked for (ViewSettings::tag); passes carry it.
  uint64_t requestedTag() const { return settings_.tag; }
  // Why the source ended by itself ("": it has not): the job ended or the connection was lost.
  const QString& endedBecause() const { return ended_; }

 public slots:
  // Takes the source's news into the frame; the source's wake() queues it.
  void takeNews();
  // The source ended by itself: says so in the title and the status bar; the last frame stays.
  void sourceEnded(const QString& why);

 signals:
  // A full-resolution pass of the view asked for last is complete (count since that view
  // started).
  void fullPassDone(int passes);
  // Every tile of this pass is in the frame shown (a view's first frame: now on screen whole).
  void passComplete(const prism::DisplayPass& pass);
  // Statistics arrived.
  void statsShown(const prism::LiveStats& stats);

 protected:
  void keyPressEvent(QKeyEvent* event) override;

 private:
  QWidget* buildSidePanel();
  QWidget* buildCausticsGroup(QWidget* parent);
  void buildMenus();
  void setDebugView(DebugView view);
  void checkDebugButton();
  void updateLightSpace();
  void updateStatusBar();

  LiveSource& source_;
  float exposure_;
  CameraController camera_;
  ViewSettings settings_;
  DisplayFrame frame_;
  FrameView* view_;
  StatsPanel* stats_;
  QSpinBox* spp_;
  QRadioButton* imageButton_;
  QRadioButton* normalsButton_;
  QRadioButton* castersButton_;
  QRadioButton* receiversButton_;
  QRadioButton* causticMapViewButton_;
  std::array<QRadioButton*, kCausticMethodCount> causticButtons_{};  // by CausticMethod
  QCheckBox* blur_;
  QSpinBox* photons_;
  QAction* tilesAction_;
  QLabel* status_;
  int fullPassesDone_ = 0;
  QString ended_;

  QString causticMapsRefusal_;  // empty: they may be built
  QString lightSpaceRefusal_;   // empty: the light-space images can be shown
  std::optional<LightSpaceMap> lightSpace_;
  std::future<std::shared_ptr<const CausticMapEstimator>> pendingMaps_;  // being built
  bool pendingBlur_ = true;
  std::shared_ptr<const CausticMapEstimator> readyMaps_;  // the last maps built
  bool readyBlur_ = true;
  QTimer* mapPoll_;  // checks a build in flight
};

}  // namespace prism
