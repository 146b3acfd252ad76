#include <gtest/gtest.h>
TEST(Security, Placeholder) {}
