#include "geardyn/core/version.hpp"
#include <cstdio>
int main() { std::printf("geardyn %s\n", geardyn::kVersion); }
