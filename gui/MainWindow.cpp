#include "gui/MainWindow.h"

#include <QAction>
#include <QApplication>
#include <QButtonGroup>
#include <QCheckBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QRadioButton>
#include <QScreen>
#include <QScrollArea>
#include <QSpinBox>
#include <QSplitter>
#include <QStatusBar>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>

#include "gui/FrameView.h"
#include "gui/SpeedupCsv.h"
#include "gui/StatsPanel.h"
#include "image/ImageIo.h"

namespace prism {
namespace {
constexpr float kTurnDegrees = 5.0f;
constexpr float kOrbitDegreesPerPixel = 0.4f;
constexpr float kZoomPerStep = 0.9f;
constexpr int kMapPollMilliseconds = 30;
}  // namespace

MainWindow::MainWindow(LiveSource& source, QWidget* parent)
    : QMainWindow(parent),
      source_(source),
      exposure_(source.start().exposure),
      camera_(source.start().home),
      settings_(source.start().view),
      frame_(source.start().width, source.start().height) {
  const ViewerStart& start = source.start();
  mapPoll_ = new QTimer(this);
  mapPoll_->setInterval(kMapPollMilliseconds);
  connect(mapPoll_, &QTimer::timeout, this, [this] { updateLightSpace(); });
  setWindowTitle("Prism — " + QString::fromStdString(start.sceneName));
  camera_.setCamera(settings_.camera);  // a resumed view may have moved from the scene's

  view_ = new FrameView(frame_, this);
  stats_ = new StatsPanel(this);
  stats_->setInstructionSet(QString::fromStdString(source.start().instructionSet));
  connect(view_, &FrameView::dragged, this, [this](int dx, int dy) {
    camera_.orbit(-kOrbitDegreesPerPixel * static_cast<float>(dx),
                  -kOrbitDegreesPerPixel * static_cast<float>(dy));
    viewChanged();
  });
  connect(view_, &FrameView::wheelTurned, this, [this](int steps) {
    camera_.zoom(std::pow(kZoomPerStep, static_cast<float>(steps)));
    viewChanged();
  });

  auto* splitter = new QSplitter(this);
  splitter->addWidget(view_);
  auto* scroll = new QScrollArea(splitter);
  scroll->setObjectName("sidePanel");
  scroll->setWidget(buildSidePanel());
  scroll->setWidgetResizable(true);
  scroll->setMinimumWidth(540);
  splitter->addWidget(scroll);
  splitter->setStretchFactor(0, 1);
  setCentralWidget(splitter);
  status_ = new QLabel(this);
  statusBar()->addWidget(status_, 1);
  buildMenus();
  view_->setFocus();
  if (!start.causticMapsRefusal.empty()) {
    refuseCausticMaps(QString::fromStdString(start.causticMapsRefusal));
  }
  lightSpaceRefusal_ = QString::fromStdString(start.lightSpaceRefusal);
  if (!lightSpaceRefusal_.isEmpty()) {
    for (QRadioButton* button : {castersButton_, receiversButton_, causticMapViewButton_}) {
      button->setEnabled(false);
      button->setToolTip("Not available: " + lightSpaceRefusal_);
    }
  }
  updateStatusBar();
}

QWidget* MainWindow::buildSidePanel() {
  auto* panel = new QWidget(this);
  auto* layout = new QVBoxLayout(panel);

  auto* render = new QGroupBox("Rendering", panel);
  auto* form = new QFormLayout(render);
  spp_ = new QSpinBox(render);
  spp_->setRange(1, 1024);
  spp_->setValue(settings_.samplesPerPixel);
  spp_->setToolTip("Samples per pixel in each full-resolution pass; passes are averaged");
  connect(spp_, qOverload<int>(&QSpinBox::valueChanged), this, [this](int spp) {
    if (spp == settings_.samplesPerPixel) return;
    settings_.samplesPerPixel = spp;
    viewChanged();
  });
  connect(spp_, &QSpinBox::editingFinished, this, [this] { view_->setFocus(); });
  form->addRow("samples / pixel / pass", spp_);
  layout->addWidget(render);

  // Debug views: per pixel from the camera (image, normals), or the caustic maps in light space.
  auto* debug = new QGroupBox("Debug view", panel);
  auto* debugLayout = new QVBoxLayout(debug);
  imageButton_ = new QRadioButton("image (n)", debug);
  normalsButton_ = new QRadioButton("normals (N)", debug);
  castersButton_ = new QRadioButton("caustic map: caster positions (R)", debug);
  receiversButton_ = new QRadioButton("caustic map: receiver positions (P)", debug);
  causticMapViewButton_ = new QRadioButton("caustic map: irradiance (C)", debug);
  castersButton_->setObjectName("debugCasters");
  receiversButton_->setObjectName("debugReceivers");
  causticMapViewButton_->setObjectName("debugCausticMap");
  imageButton_->setChecked(true);
  auto* group = new QButtonGroup(debug);
  const std::pair<QRadioButton*, std::function<void()>> choices[] = {
      {imageButton_, [this] { setDebugView(DebugView::Image); }},
      {normalsButton_, [this] { setDebugView(DebugView::Normals); }},
      {castersButton_, [this] { showLightSpace(LightSpaceMap::Casters); }},
      {receiversButton_, [this] { showLightSpace(LightSpaceMap::Receivers); }},
      {causticMapViewButton_, [this] { showLightSpace(LightSpaceMap::Caustics); }}};
  for (const auto& [button, choose] : choices) {
    group->addButton(button);
    connect(button, &QRadioButton::toggled, this, [choose = choose](bool on) {
      if (on) choose();
    });
    debugLayout->addWidget(button);
  }
  layout->addWidget(debug);

  layout->addWidget(buildCausticsGroup(panel));

  auto* statsGroup = new QGroupBox("Statistics", panel);
  auto* statsLayout = new QVBoxLayout(statsGroup);
  statsLayout->addWidget(stats_);
  layout->addWidget(statsGroup, 1);
  return panel;
}

QWidget* MainWindow::buildCausticsGroup(QWidget* parent) {
  auto* group = new QGroupBox("Caustics", parent);
  auto* form = new QFormLayout(group);
  // One button a method of scene/CausticMethods.h, named "caustics" and the method's enumerator.
  auto* buttons = new QButtonGroup(group);
  for (const CausticMethodInfo& info : kCausticMethods) {
    auto* button = new QRadioButton(info.title, group);
    static const char* const kObjectNames[] = {
#define PRISM_CAUSTIC_BUTTON_NAME(Method, name, title, description) "caustics" #Method,
        PRISM_CAUSTIC_METHODS(PRISM_CAUSTIC_BUTTON_NAME)
#undef PRISM_CAUSTIC_BUTTON_NAME
    };
    button->setObjectName(kObjectNames[static_cast<size_t>(info.method)]);
    button->setToolTip(info.description);
    causticButtons_[static_cast<size_t>(info.method)] = button;
    buttons->addButton(button);
    button->setChecked(settings_.caustics == info.method);
    connect(button, &QRadioButton::toggled, this, [this, method = info.method](bool on) {
      if (on) setCausticMethod(method);
    });
    form->addRow(button);
  }
  blur_ = new QCheckBox("caustic map blur (b)", group);
  blur_->setObjectName("causticMapBlur");
  blur_->setChecked(settings_.causticMapBlur);
  blur_->setToolTip(
      "The scene's Gaussian filter over the caustic map (map_blur_sigma, "
      "map_blur_radius); off shows the raw splats");
  connect(blur_, &QCheckBox::toggled, this, [this](bool on) { setCausticMapBlur(on); });
  form->addRow(blur_);
  photons_ = new QSpinBox(group);
  photons_->setObjectName("photonsPerPass");
  constexpr int kMaxPhotons = 20'000'000;  // far beyond an interactive pass on a laptop
  photons_->setRange(1000, kMaxPhotons);
  photons_->setSingleStep(10000);
  photons_->setGroupSeparatorShown(true);
  photons_->setValue(static_cast<int>(
      std::clamp<uint64_t>(settings_.photonsPerPass, 1000, static_cast<uint64_t>(kMaxPhotons))));
  settings_.photonsPerPass = static_cast<uint64_t>(photons_->value());
  photons_->setKeyboardTracking(false);  // a new view when the number is entered, not per digit
  photons_->setToolTip("Photons emitted towards the caustic casters in each full pass");
  connect(photons_, qOverload<int>(&QSpinBox::valueChanged), this,
          [this](int photons) { setPhotonsPerPass(static_cast<uint64_t>(photons)); });
  connect(photons_, &QSpinBox::editingFinished, this, [this] { view_->setFocus(); });
  form->addRow("photons / pass", photons_);
  return group;
}

void MainWindow::setCausticMethod(CausticMethod method) {
  if (method == CausticMethod::CausticMap && !causticMapsRefusal_.isEmpty()) {
    statusBar()->showMessage("caustic maps refused: " + causticMapsRefusal_, 15000);
    method = settings_.caustics;  // the switch goes back to the method in use
  }
  causticButtons_[static_cast<size_t>(method)]->setChecked(true);
  if (settings_.caustics == method) return;
  settings_.caustics = method;
  viewChanged();
}

void MainWindow::setCausticMapBlur(bool blur) {
  if (settings_.causticMapBlur == blur) return;
  settings_.causticMapBlur = blur;
  if (blur_->isChecked() != blur) blur_->setChecked(blur);
  if (settings_.caustics == CausticMethod::CausticMap) viewChanged();
  if (lightSpace_) showLightSpace(*lightSpace_);  // the irradiance map changes with the blur
}

void MainWindow::refuseCausticMaps(const QString& why) {
  causticMapsRefusal_ = why;
  for (QRadioButton* button : {causticButtons_[static_cast<size_t>(CausticMethod::CausticMap)],
                               castersButton_, receiversButton_, causticMapViewButton_}) {
    button->setEnabled(false);
    button->setToolTip("Not available: " + why);
  }
}

void MainWindow::showLightSpace(LightSpaceMap which) {
  lightSpace_ = which;
  checkDebugButton();
  if (!lightSpaceRefusal_.isEmpty()) {
    view_->setOverlay({}, lightSpaceRefusal_ + " · n: back to the image");
    return;
  }
  if (!causticMapsRefusal_.isEmpty()) {
    view_->setOverlay({},
                      "caustic maps refused: " + causticMapsRefusal_ + " · n: back to the image");
    return;
  }
  updateLightSpace();
}

void MainWindow::updateLightSpace() {
  if (!lightSpace_ || !lightSpaceRefusal_.isEmpty()) return mapPoll_->stop();
  if (pendingMaps_.valid() &&
      pendingMaps_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    readyMaps_ = pendingMaps_.get();
    readyBlur_ = pendingBlur_;
  }
  const bool blur = settings_.causticMapBlur;
  if (readyMaps_ && readyBlur_ == blur) {
    mapPoll_->stop();
    view_->setOverlay(lightSpaceImage(*readyMaps_, *lightSpace_),
                      lightSpaceCaption(*readyMaps_, *lightSpace_, blur));
    return;
  }
  if (!pendingMaps_.valid()) {  // one build at a time; a stale one finishes first
    pendingBlur_ = blur;
    pendingMaps_ =
        std::async(std::launch::async, [this, blur] { return source_.causticMaps(blur); });
  }
  if (!mapPoll_->isActive()) {
    view_->setOverlay({}, "building the caustic maps…");
    mapPoll_->start();
  }
}

void MainWindow::checkDebugButton() {
  QRadioButton* button = settings_.debugView == DebugView::Normals ? normalsButton_ : imageButton_;
  if (lightSpace_) {
    button = *lightSpace_ == LightSpaceMap::Casters     ? castersButton_
             : *lightSpace_ == LightSpaceMap::Receivers ? receiversButton_
                                                        : causticMapViewButton_;
  }
  if (!button->isChecked()) button->setChecked(true);
}

void MainWindow::setPhotonsPerPass(uint64_t photons) {
  photons = std::clamp<uint64_t>(photons, static_cast<uint64_t>(photons_->minimum()),
                                 static_cast<uint64_t>(photons_->maximum()));
  if (settings_.photonsPerPass == photons) return;
  settings_.photonsPerPass = photons;
  if (photons_->value() != static_cast<int>(photons)) photons_->setValue(static_cast<int>(photons));
  if (settings_.caustics == CausticMethod::PhotonMap) viewChanged();  // otherwise nothing changes
}

void MainWindow::buildMenus() {
  QMenu* file = menuBar()->addMenu("&File");
  QAction* save = file->addAction("&Save image…");
  save->setShortcut(QKeySequence::Save);
  connect(save, &QAction::triggered, this, [this] {
    const QString path =
        QFileDialog::getSaveFileName(this, "Save image", "prism.png", "Images (*.png *.exr)");
    if (path.isEmpty()) return;
    try {
      saveImage(path);
      statusBar()->showMessage("saved " + path, 5000);
    } catch (const std::exception& e) {
      QMessageBox::warning(this, "Save image", e.what());
    }
  });
  QAction* csv = file->addAction("&Load speedup CSV…");
  csv->setShortcut(QKeySequence::Open);
  connect(csv, &QAction::triggered, this, [this] {
    const QString path =
        QFileDialog::getOpenFileName(this, "Load speedup CSV", QString(), "CSV (*.csv)");
    if (path.isEmpty()) return;
    const QString error = loadSpeedupCsv(path);
    if (!error.isEmpty()) QMessageBox::warning(this, "Load speedup CSV", error);
  });
  file->addSeparator();
  QAction* quit = file->addAction("&Quit (q)");
  connect(quit, &QAction::triggered, this, &QWidget::close);

  QMenu* viewMenu = menuBar()->addMenu("&View");
  tilesAction_ = viewMenu->addAction("Show &tiles in flight (t)");
  tilesAction_->setCheckable(true);
  tilesAction_->setChecked(view_->showTiles());
  connect(tilesAction_, &QAction::toggled, view_, &FrameView::setShowTiles);
  QAction* help = viewMenu->addAction("&Keys (h, F1)");
  connect(help, &QAction::triggered, this, [this] { view_->setShowHelp(!view_->showHelp()); });
}

void MainWindow::fitToScreen(const QSize& preferred) {
  const QScreen* screen = this->screen() ? this->screen() : QGuiApplication::primaryScreen();
  if (!screen) {
    resize(preferred);
    return;
  }
  const QRect area = screen->availableGeometry();
  // The title bar and borders are not known before the window is shown: leave them room.
  const QSize room(area.width() * 96 / 100, area.height() * 90 / 100);
  const QSize size = preferred.boundedTo(room).expandedTo(minimumSizeHint());
  resize(size);
  move(area.center() - QPoint(size.width() / 2, size.height() / 2));
}

void MainWindow::startRendering() {
  if (source_.start().resume) {
    // What has accumulated (the source sends every pixel first), queued behind the keys a
    // script typed, so that their views are asked for before any pass is counted.
    QMetaObject::invokeMethod(this, &MainWindow::takeNews, Qt::QueuedConnection);
    return;
  }
  ++settings_.tag;
  source_.setView(settings_);
}

void MainWindow::viewChanged() {
  settings_.camera = camera_.camera();
  ++settings_.tag;
  source_.setView(settings_);
}

void MainWindow::setDebugView(DebugView view) {
  const bool leftLightSpace = lightSpace_.has_value();
  lightSpace_.reset();
  mapPoll_->stop();
  view_->clearOverlay();
  if (settings_.debugView == view) {
    if (leftLightSpace) checkDebugButton();
    return;
  }
  settings_.debugView = view;
  checkDebugButton();
  viewChanged();
}

MainWindow::~MainWindow() {
  if (pendingMaps_.valid()) pendingMaps_.wait();  // a build in flight uses the renderer
}

void MainWindow::saveImage(const QString& path) {
  const std::string file = path.toStdString();
  if (path.endsWith(".png", Qt::CaseInsensitive)) {
    writeDisplayPng(file, frame_.width(), frame_.height(), frame_.bytes());
  } else {
    writeImage(source_.fullImage(), file, exposure_);
  }
}

QString MainWindow::loadSpeedupCsv(const QString& path) {
  try {
    stats_->setSpeedupTable(readSpeedupCsv(path.toStdString()), QFileInfo(path).fileName());
    return {};
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

void MainWindow::keyPressEvent(QKeyEvent* event) {
  // Letters by the text typed, so Shift tells q (quit) from Q (down) and n from N.
  const QString text = event->text();
  const QChar c = text.size() == 1 ? text[0] : QChar();
  bool cameraMoved = true;
  if (c == 'w' || c == 'W') {
    camera_.move(1, 0, 0);
  } else if (c == 's' || c == 'S') {
    camera_.move(-1, 0, 0);
  } else if (c == 'a' || c == 'A') {
    camera_.move(0, -1, 0);
  } else if (c == 'd' || c == 'D') {
    camera_.move(0, 1, 0);
  } else if (c == 'Q') {
    camera_.move(0, 0, -1);
  } else if (c == 'E' || c == 'e') {
    camera_.move(0, 0, 1);
  } else if (event->key() == Qt::Key_Left) {
    camera_.rotate(kTurnDegrees, 0);
  } else if (event->key() == Qt::Key_Right) {
    camera_.rotate(-kTurnDegrees, 0);
  } else if (event->key() == Qt::Key_Up) {
    camera_.rotate(0, kTurnDegrees);
  } else if (event->key() == Qt::Key_Down) {
    camera_.rotate(0, -kTurnDegrees);
  } else if (c == 'r') {
    camera_.reset();
  } else {
    cameraMoved = false;
  }
  if (cameraMoved) {
    viewChanged();
    return;
  }
  if (c == 'N') {
    setDebugView(DebugView::Normals);
  } else if (c == 'n') {
    setDebugView(DebugView::Image);
  } else if (c == 'R') {
    showLightSpace(LightSpaceMap::Casters);
  } else if (c == 'P') {
    showLightSpace(LightSpaceMap::Receivers);
  } else if (c == 'C') {
    showLightSpace(LightSpaceMap::Caustics);
  } else if (c == 'b') {
    setCausticMapBlur(!settings_.causticMapBlur);
  } else if (c == 'q') {
    close();
  } else if (c == 't') {
    tilesAction_->toggle();
  } else if (c == '+' || c == '=') {
    spp_->setValue(spp_->value() + 1);
  } else if (c == '-') {
    spp_->setValue(spp_->value() - 1);
  } else if (c == 'h' || event->key() == Qt::Key_F1) {
    view_->setShowHelp(!view_->showHelp());
  } else if (event->key() == Qt::Key_Escape && view_->showHelp()) {
    view_->setShowHelp(false);
  } else {
    QMainWindow::keyPressEvent(event);
  }
}

void MainWindow::takeNews() {
  DisplayNews news = source_.take();
  const bool newView = news.pass.viewId != frame_.pass().viewId;
  frame_.apply(news);
  if (newView) fullPassesDone_ = 0;
  view_->markChanged();
  for (const DisplayPass& pass : news.completed) emit passComplete(pass);
  // Passes of the view asked for last: those a script waits for.
  if (news.started && news.pass.viewTag == settings_.tag && news.fullPassesDone > fullPassesDone_) {
    fullPassesDone_ = news.fullPassesDone;
    emit fullPassDone(fullPassesDone_);
  }
  if (news.stats) {
    stats_->showStats(*news.stats);
    emit statsShown(*news.stats);
  }
  updateStatusBar();
}

void MainWindow::sourceEnded(const QString& why) {
  ended_ = why;
  setWindowTitle(windowTitle() + " (ended)");
  updateStatusBar();
}

void MainWindow::updateStatusBar() {
  if (!ended_.isEmpty()) {
    status_->setText(ended_ + " · the last frame stays · q: quit");
    return;
  }
  const DisplayPass& p = frame_.pass();
  const QString what =
      p.pass == 0
          ? QString("moving, %1 resolution, 1 spp").arg(QString::fromStdString(p.scale.text()))
          : QString("pass %1 (%2 spp each)").arg(p.pass).arg(p.samplesPerPixel);
  status_->setText(QString("frame %1 · %2 · tiles %3/%4 · %5 spp averaged · h: keys")
                       .arg(p.frame)
                       .arg(what)
                       .arg(frame_.state().tilesDone)
                       .arg(p.tiles)
                       .arg(frame_.state().fullPassesDone * p.samplesPerPixel));
}

}  // namespace prism
