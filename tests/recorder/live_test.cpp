// The live view's protocol (live::Hub, live.hpp) without a socket: what a client gets first, what a
// subscription delivers, and that bad client input is answered with an error status and counted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "mpgc/recorder/live.hpp"

namespace live = mpgc::recorder::live;
using nlohmann::json;

namespace {

live::Channel nav(uint32_t id) { return {id, "nav/own_state", "cdr", "mpgc::msg::NavState", "module mpgc { };", "omgidl"}; }
live::Channel fix(uint32_t id) { return {id, "map/own_ship", "json", "foxglove.LocationFix", "{}", "jsonschema"}; }

json text(const live::Frame& f) {
  EXPECT_FALSE(f.binary);
  return json::parse(f.bytes);
}

uint64_t le(const std::string& s, size_t at, int bytes) {
  uint64_t v = 0;
  for (int k = 0; k < bytes; ++k) v |= static_cast<uint64_t>(static_cast<unsigned char>(s[at + k])) << (8 * k);
  return v;
}

// One error status, naming `what`.
void expect_error(const std::vector<live::Frame>& out, const std::string& what) {
  ASSERT_EQ(out.size(), 1u);
  const json j = text(out[0]);
  EXPECT_EQ(j["op"], "status");
  EXPECT_EQ(j["level"], 2);
  EXPECT_NE(j["message"].get<std::string>().find(what), std::string::npos) << j.dump();
}

}  // namespace

TEST(LiveProtocol, MessageDataIsOpcodeSubscriptionTimeAndPayloadLittleEndian) {
  const std::string f = live::message_data(0x01020304u, 0x1122334455667788ull, "abc", 3);
  ASSERT_EQ(f.size(), 1u + 4 + 8 + 3);
  EXPECT_EQ(f[0], 0x01);
  EXPECT_EQ(le(f, 1, 4), 0x01020304u);
  EXPECT_EQ(le(f, 5, 8), 0x1122334455667788ull);
  EXPECT_EQ(f.substr(13), "abc");
}

TEST(LiveProtocol, SubprotocolIsFoundInTheOfferedList) {
  EXPECT_TRUE(live::offers_subprotocol("foxglove.websocket.v1"));
  EXPECT_TRUE(live::offers_subprotocol("chat, foxglove.websocket.v1 ,x"));
  EXPECT_FALSE(live::offers_subprotocol(""));
  EXPECT_FALSE(live::offers_subprotocol("foxglove.websocket.v2"));
  EXPECT_FALSE(live::offers_subprotocol("foxglove.websocket.v1x"));
}

TEST(LiveHub, ClientGetsServerInfoThenEveryChannel) {
  live::Hub hub("mpgc_record", "s1");
  ASSERT_TRUE(hub.add_channel(nav(1)));
  ASSERT_TRUE(hub.add_channel(fix(2)));
  const auto first = hub.open(7);
  ASSERT_EQ(first.size(), 2u);
  const json info = text(first[0]);
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "mpgc_record");
  EXPECT_EQ(info["sessionId"], "s1");
  EXPECT_TRUE(info["capabilities"].is_array());
  const json adv = text(first[1]);
  EXPECT_EQ(adv["op"], "advertise");
  ASSERT_EQ(adv["channels"].size(), 2u);
  const json& c = adv["channels"][0];
  EXPECT_EQ(c["id"], 1);
  EXPECT_EQ(c["topic"], "nav/own_state");
  EXPECT_EQ(c["encoding"], "cdr");
  EXPECT_EQ(c["schemaName"], "mpgc::msg::NavState");
  EXPECT_EQ(c["schema"], "module mpgc { };");
  EXPECT_EQ(c["schemaEncoding"], "omgidl");
  EXPECT_EQ(adv["channels"][1]["encoding"], "json");
  EXPECT_EQ(adv["channels"][1]["schemaEncoding"], "jsonschema");
}

TEST(LiveHub, ChannelIdsAreUniqueAndNewOnesAreAdvertised) {
  live::Hub hub("n", "s");
  EXPECT_FALSE(hub.add_channel(nav(0)));  // 0 is not an id
  ASSERT_TRUE(hub.add_channel(nav(1)));
  EXPECT_FALSE(hub.add_channel(fix(1)));
  hub.open(1);
  const auto adv = hub.add_channel(fix(2));
  ASSERT_TRUE(adv);
  const json j = text(*adv);
  ASSERT_EQ(j["channels"].size(), 1u);
  EXPECT_EQ(j["channels"][0]["topic"], "map/own_ship");
  EXPECT_EQ(hub.channels().size(), 2u);
}

TEST(LiveHub, SamplesGoToSubscribersOnlyWithTheirSubscriptionId) {
  live::Hub hub("n", "s");
  hub.add_channel(nav(1));
  hub.add_channel(fix(2));
  hub.open(1);
  hub.open(2);
  EXPECT_TRUE(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":40,"channelId":1}]})").empty());
  EXPECT_TRUE(hub.on_text(2, R"({"op":"subscribe","subscriptions":[{"id":9,"channelId":2},{"id":10,"channelId":1}]})").empty());
  auto out = hub.sample(1, 123, "xy", 2);
  ASSERT_EQ(out.size(), 2u);
  for (const auto& [c, f] : out) {
    EXPECT_TRUE(f.binary);
    EXPECT_EQ(le(f.bytes, 1, 4), c == 1 ? 40u : 10u);
    EXPECT_EQ(le(f.bytes, 5, 8), 123u);
    EXPECT_EQ(f.bytes.substr(13), "xy");
  }
  EXPECT_EQ(hub.sample(2, 5, "{}", 2).size(), 1u);
  EXPECT_TRUE(hub.on_text(2, R"({"op":"unsubscribe","subscriptionIds":[10]})").empty());
  out = hub.sample(1, 124, "z", 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].first, 1u);
  hub.close(1);
  EXPECT_TRUE(hub.sample(1, 125, "z", 1).empty());
  EXPECT_TRUE(hub.sample(99, 125, "z", 1).empty());  // a channel never added: nothing, no throw
  EXPECT_EQ(hub.errors(), 0u);
}

TEST(LiveHub, ANewSubscriberGetsTheChannelsLastSample) {
  live::Hub hub("n", "s");
  hub.add_channel(fix(3));
  hub.sample(3, 10, "old", 3);
  hub.sample(3, 20, "chart", 5);
  hub.open(1);
  const auto out = hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":3}]})");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].binary);
  EXPECT_EQ(le(out[0].bytes, 5, 8), 20u);
  EXPECT_EQ(out[0].bytes.substr(13), "chart");
}

TEST(LiveHub, BadClientInputIsAnsweredWithAnErrorAndCounted) {
  live::Hub hub("n", "s");
  hub.add_channel(nav(1));
  hub.open(1);
  expect_error(hub.on_text(1, "not json {"), "not JSON");
  expect_error(hub.on_text(1, "[1,2]"), "\"op\"");
  expect_error(hub.on_text(1, R"({"op":3})"), "\"op\"");
  expect_error(hub.on_text(1, R"({"op":"advertise","channels":[]})"), "not supported");
  expect_error(hub.on_text(1, R"({"op":"subscribe"})"), "subscriptions");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":{"id":1}})"), "subscriptions");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":1}]})"), "channelId");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})"), "unsigned 32-bit");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})"), "unsigned 32-bit");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})"), "unsigned 32-bit");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":"1","channelId":1}]})"), "unsigned 32-bit");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":77}]})"), "not advertised");
  EXPECT_TRUE(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})").empty());
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})"), "already in use");
  expect_error(hub.on_text(1, R"({"op":"subscribe","subscriptions":[{"id":2,"channelId":1}]})"), "already subscribed");
  expect_error(hub.on_text(1, R"({"op":"unsubscribe","subscriptionIds":[5]})"), "not a subscription id");
  expect_error(hub.on_text(1, R"({"op":"unsubscribe","subscriptionIds":["\u00ff"]})"), "not a subscription id");
  expect_error(hub.on_text(1, R"({"op":"unsubscribe"})"), "subscriptionIds");
  expect_error(hub.on_binary(1, 12), "no client publishing");
  EXPECT_EQ(hub.errors(), 18u);
  // Deeply nested and invalid UTF-8 input: an error, no crash.
  expect_error(hub.on_text(1, std::string(100000, '[') + std::string(100000, ']')), "\"op\"");
  expect_error(hub.on_text(1, std::string("{\"op\":\"\xff\xfe\"}")), "not JSON");
  expect_error(hub.on_text(1, R"({"op":"x\u00e9"})"), "not supported");
  // The good subscription survived all that.
  EXPECT_EQ(hub.subscriptions(1, 1), std::vector<uint32_t>{1});
  // A client that is gone: nothing to answer.
  EXPECT_TRUE(hub.on_text(2, R"({"op":"subscribe"})").empty());
}

TEST(LiveWeb, PageAndScriptAreServedAndOtherPathsAreNot) {
  const auto index = live::web_file("/");
  ASSERT_TRUE(index);
  EXPECT_NE(index->content_type.find("text/html"), std::string::npos);
  EXPECT_NE(index->body.find("view.js"), std::string::npos);
  EXPECT_EQ(live::web_file("/index.html?x=1")->body, index->body);
  const auto js = live::web_file("/view.js");
  ASSERT_TRUE(js);
  EXPECT_NE(js->body.find("foxglove.websocket.v1"), std::string::npos);
  EXPECT_FALSE(live::web_file("/../CMakeLists.txt"));
  EXPECT_FALSE(live::web_file("/etc/passwd"));
  // Nothing from elsewhere: no http(s) address in the page or its script.
  EXPECT_EQ(index->body.find("http"), std::string::npos);
  EXPECT_EQ(js->body.find("http"), std::string::npos);
}

TEST(LiveViewState, IsJsonWithNullForNonFiniteNumbers) {
  live::ViewState v;
  v.t_ns = 2500000000ull;
  v.own_sog = 5.5;
  v.plan_status = "PLAN_RELAXED";
  v.plan_reason = std::string("r\xff");
  v.plan_id = 3;
  v.safety_distance = 500;
  v.targets.push_back({"mmsi_257", 4, 63.4, 10.3, NAN, 3.0});
  v.encounters.push_back({4, 257, "ENCOUNTER_HEAD_ON", "ROLE_GIVE_WAY", 120, INFINITY, 900});
  const json j = json::parse(live::view_state_json(v));
  EXPECT_EQ(j["timestamp"]["sec"], 2);
  EXPECT_EQ(j["timestamp"]["nsec"], 500000000);
  EXPECT_EQ(j["own_sog"], 5.5);
  EXPECT_EQ(j["plan"]["status"], "PLAN_RELAXED");
  EXPECT_EQ(j["plan"]["id"], 3);
  EXPECT_EQ(j["targets"][0]["name"], "mmsi_257");
  EXPECT_TRUE(j["targets"][0]["cog"].is_null());
  EXPECT_EQ(j["encounters"][0]["situation"], "ENCOUNTER_HEAD_ON");
  EXPECT_TRUE(j["encounters"][0]["tcpa"].is_null());
  EXPECT_NO_THROW(json::parse(live::kViewStateSchema));
}
