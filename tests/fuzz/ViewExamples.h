// One example of every viewer protocol message, with every field set: the view fuzzer's seeds
// (ViewSeeds.cpp) and the protocol's round-trip tests.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "master/remote/ViewProtocol.h"

namespace prism::fuzz {

inline DisplayNews exampleNews() {
  DisplayNews news;
  news.started = true;
  news.width = 8;
  news.height = 4;
  news.pass = {7, 3, 2, 1, FrameScale{2, 3}, true, CameraDesc{}, 4, CausticMethod::PhotonMap, 6};
  news.tilesDone = 5;
  news.completedPass = 1;
  news.fullPassesDone = 1;
  news.staleTiles = 2;
  news.completed = {news.pass};
  news.inFlight = {{{0, 0, 4, 2}, 1}, {{4, 2, 4, 2}, 2}};
  news.patch = {1, 1, 3, 2};
  for (int i = 0; i < 3 * 2 * 3; ++i) news.patchBytes.push_back(static_cast<uint8_t>(i * 13));
  LiveStats stats;
  stats.frame = 7;
  stats.ranks.resize(2);
  stats.ranks[1].rank = 1;
  stats.ranks[1].rays.primary = 1234;
  stats.ranks[1].retired = true;
  stats.raysPerSecond = 1.5e6;
  stats.frameTimes.frames = 12;
  stats.photons.method = CausticMethod::PhotonMap;
  stats.photons.radius = 0.25f;
  news.stats = stats;
  return news;
}

inline std::vector<std::pair<std::string, std::vector<uint8_t>>> viewExamples() {
  using namespace prism::view;
  ViewerStart start;
  start.sceneName = "default.yaml";
  start.width = 640;
  start.height = 360;
  start.exposure = 1.5f;
  start.view.samplesPerPixel = 2;
  start.view.caustics = CausticMethod::CausticMap;
  start.view.tag = 9;
  start.view.maxPasses = 3;
  start.resume = true;
  start.causticMapsRefusal = "too big";
  ViewSettings view = start.view;
  view.debugView = DebugView::Normals;
  view.causticMapBlur = false;
  view.photonsPerPass = 50000;
  view.frameTimeSeconds = 0.02;
  FullImageMessage image;
  image.request = 4;
  image.image = ImageRgb(3, 2);
  image.image.pixels[1] = Color(0.5f, 2.0f, -0.0f);
  return {{"hello", encode(HelloMessage{std::string(64, 'a'), "prism connect, me@desk"})},
          {"welcome", encode(WelcomeMessage{start})},
          {"refused", encode(RefusedMessage{"wrong token"})},
          {"set-view", encode(view)},
          {"news", encode(exampleNews())},
          {"full-image-request", encode(FullImageRequestMessage{4})},
          {"full-image", encode(image)},
          {"ping", encode(PingMessage{})},
          {"bye", encode(ByeMessage{})},
          {"job-ended", encode(JobEndedMessage{"the job was interrupted (SIGINT)"})},
          {"news-received", encode(NewsReceivedMessage{12})}};
}

}  // namespace prism::fuzz
