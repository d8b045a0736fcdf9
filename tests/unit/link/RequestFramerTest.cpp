#include "core/link/RequestFramer.h"

#include <gtest/gtest.h>

using namespace scanpick::core::link;

TEST(RequestFramer, CutsAMixedStreamFedByteByByte) {
  Request bin;
  bin.command = Command::Trigger;
  bin.id = 5;
  const std::string stream = "\n{\"cmd\":\"status\"}\n" + encodeBinaryRequest(bin) +
                             "  {\"cmd\":\"next\",\"id\":2}\r\n" + encodeBinaryRequest(bin);
  RequestFramer f;
  std::vector<Frame> frames;
  for (char c : stream) {
    f.feed(std::string_view(&c, 1));
    while (auto frame = f.next())
      frames.push_back(*frame);
  }
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].kind, Frame::Kind::Json);
  EXPECT_EQ(frames[0].bytes, "{\"cmd\":\"status\"}");
  EXPECT_EQ(frames[1].kind, Frame::Kind::Binary);
  EXPECT_EQ(frames[1].bytes, encodeBinaryRequest(bin));
  EXPECT_EQ(frames[2].kind, Frame::Kind::Json);
  EXPECT_EQ(frames[3].kind, Frame::Kind::Binary);
  EXPECT_FALSE(f.hasPartial());
  EXPECT_TRUE(f.sawBinary());
}

TEST(RequestFramer, PartialMessagesWaitAndSayWhatTheyAre) {
  RequestFramer f;
  f.feed("SPK1\x01");
  EXPECT_FALSE(f.next());
  EXPECT_TRUE(f.hasPartial());
  EXPECT_TRUE(f.partialIsBinary());
  RequestFramer g;
  g.feed("  {\"cmd\":");
  EXPECT_FALSE(g.next());
  EXPECT_TRUE(g.hasPartial());
  EXPECT_FALSE(g.partialIsBinary());
  RequestFramer h;
  h.feed(" \r\n");
  EXPECT_FALSE(h.hasPartial());
}

TEST(RequestFramer, GarbageAndOverlongLinesEndTheStream) {
  RequestFramer text;
  text.feed("hello\n{\"cmd\":\"status\"}\n");
  auto e = text.next();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->kind, Frame::Kind::Error);
  EXPECT_EQ(e->error, Status::BadMagic);
  EXPECT_FALSE(e->binary_reply); // printable: answered in JSON
  EXPECT_FALSE(text.next());     // nothing after an error
  EXPECT_TRUE(text.failed());

  RequestFramer binary;
  binary.feed(std::string("\x00\x01\x02", 3));
  e = binary.next();
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->binary_reply);

  RequestFramer wrong_magic;
  wrong_magic.feed("SPX");
  e = wrong_magic.next();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->error, Status::BadMagic);

  RequestFramer longline;
  longline.feed("{" + std::string(kMaxJsonLine + 10, ' '));
  e = longline.next();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->error, Status::TooLong);
}
