// anyphys::Error: the kind and field travel with the message, through the wrappers that add context.
#include <gtest/gtest.h>

#include "anyphys/containers/scene.hpp"
#include "anyphys/error.hpp"

using namespace anyphys;

TEST(Error, MessageOnlyKeepsTheOldMeaning) {
    const Error e("something went wrong");
    EXPECT_STREQ(e.what(), "something went wrong");
    EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument);
    EXPECT_TRUE(e.field().empty());
}

TEST(Error, InvalidNamesTheFieldAndKeepsTheMessageFormat) {
    const Error e = Error::invalid("BodyDef.shape.radius", -1, "must be > 0");
    EXPECT_STREQ(e.what(), "BodyDef.shape.radius: must be > 0, got -1");
    EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument);
    EXPECT_EQ(e.field(), "BodyDef.shape.radius");
    EXPECT_EQ(Error::invalid("f", 1, "r", ErrorKind::Unsupported).kind(), ErrorKind::Unsupported);
}

TEST(Error, WithinAddsContextAndKeepsKindAndField) {
    const Error e = Error(ErrorKind::Parse, "settings.gravityy", "settings.gravityy: unknown key").within("scene.json");
    EXPECT_STREQ(e.what(), "scene.json: settings.gravityy: unknown key");
    EXPECT_EQ(e.kind(), ErrorKind::Parse);
    EXPECT_EQ(e.field(), "settings.gravityy");
}

TEST(Error, RenamedNamesTheNewFieldInItsPlace) {
    const Error e = Error::invalid("backend", "\"x\"", "must be one of native, ode").renamed("--backends");
    EXPECT_STREQ(e.what(), "--backends: must be one of native, ode, got \"x\"");
    EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument);
    EXPECT_EQ(e.field(), "--backends");
    // A message that does not begin with its field keeps all of it, after the new field.
    const Error plain = Error(ErrorKind::Io, "path", "cannot open").renamed("--out");
    EXPECT_STREQ(plain.what(), "--out: cannot open");
    EXPECT_EQ(plain.kind(), ErrorKind::Io);
}

TEST(Error, EveryKindHasAName) {
    for (ErrorKind k : {ErrorKind::InvalidArgument, ErrorKind::InvalidState, ErrorKind::StaleHandle, ErrorKind::Unsupported,
                        ErrorKind::Parse, ErrorKind::Diverged, ErrorKind::Io, ErrorKind::Internal})
        EXPECT_FALSE(toString(k).empty());
    EXPECT_EQ(toString(ErrorKind::StaleHandle), "stale_handle");
}

TEST(Error, SceneFilesReportIoAndKeepFieldsThroughTheFileName) {
    try {
        (void)loadScene("/nonexistent/dir/scene.json");
        ADD_FAILURE() << "expected an Io error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Io) << e.what();
    }
}
