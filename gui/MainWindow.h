// The viewer window: the live frame in the middle, a side panel with the render controls and
// the statistics, menus for saving the image and loading a speedup table, and the keys listed
// in gui/HelpText.h. Every camera or setting change asks the renderer for a new view, which
// starts a new frame; tiles of the old one are ignored when they arrive.
#pragma once

#include <QMainWindow>
#include <functional>
#include <future>
#include <optional>

#include "gui/CameraController.h"
#include "gui/FrameAccumulator.h"
#include "gui/LightSpaceImage.h"
#include "master/runtime/LiveRenderer.h"

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
  using ViewRequest = std::function<void(const ViewSettings&)>;
  // The scene's caustic maps with the blur on or off (LiveRenderer::causticMaps); called on a
  // worker thread, so it may take a while.
  using CausticMapSource = std::function<std::shared_ptr<const CausticMapEstimator>(bool blur)>;

  MainWindow(const SceneDescription& scene, const QString& sceneName, ViewRequest requestView,
             CausticMapSource causticMaps = {}, QWidget* parent = nullptr);
  ~MainWindow() override;

  // Asks for the first view (the scene's camera); call once the renderer runs.
  void startRendering();

  // Sizes the window to `preferred` where the screen it opens on has room, else to the room
  // there is (on a 1280x800 screen the side panel stays on screen), and centres it there.
  // The frame keeps its aspect ratio inside whatever the view gets (FrameView::imageRect).
  void fitToScreen(const QSize& preferred);

  // Saves the current image (PNG tone-mapped, EXR linear); throws std::runtime_error.
  void saveImage(const QString& path) const;
  // Loads a speedup CSV into the chart; returns an error message, empty on success.
  QString loadSpeedupCsv(const QString& path);

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
  const FrameAccumulator& frame() const { return frame_; }
  FrameView* frameView() const { return view_; }
  StatsPanel* statsPanel() const { return stats_; }
  int fullPassesDone() const { return fullPassesDone_; }
  uint64_t viewId() const { return frame_.pass().viewId; }

 public slots:
  void onPassStarted(const prism::PassInfo& pass);
  void onTileAssigned(uint32_t frame, uint32_t tile, int rank);
  void onTileFinished(uint32_t frame, std::shared_ptr<const prism::TileResult> tile, int rank);
  void onPassFinished(uint32_t frame, double seconds);
  void onStats(const prism::LiveStats& stats);

 signals:
  // A full-resolution pass of the current view is complete (count since the view started).
  void fullPassDone(int passes);
  // Every tile of this pass is in the frame shown (a view's first frame: now on screen whole).
  void passComplete(const prism::PassInfo& pass);

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

  float exposure_;
  ViewRequest requestView_;
  CameraController camera_;
  ViewSettings settings_;
  FrameAccumulator frame_;
  FrameView* view_;
  StatsPanel* stats_;
  QSpinBox* spp_;
  QRadioButton* imageButton_;
  QRadioButton* normalsButton_;
  QRadioButton* castersButton_;
  QRadioButton* receiversButton_;
  QRadioButton* causticMapViewButton_;
  QRadioButton* noCausticsButton_;
  QRadioButton* photonMapButton_;
  QRadioButton* causticMapButton_;
  QCheckBox* blur_;
  QSpinBox* photons_;
  QAction* tilesAction_;
  QLabel* status_;
  int fullPassesDone_ = 0;

  CausticMapSource causticMaps_;
  QString causticMapsRefusal_;  // empty: they may be built
  std::optional<LightSpaceMap> lightSpace_;
  std::future<std::shared_ptr<const CausticMapEstimator>> pendingMaps_;  // being built
  bool pendingBlur_ = true;
  std::shared_ptr<const CausticMapEstimator> readyMaps_;  // the last maps built
  bool readyBlur_ = true;
  QTimer* mapPoll_;  // checks a build in flight
};

}  // namespace prism
