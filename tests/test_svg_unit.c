#include "svg_check.h"
void test_svg_unit(const svg_test_opts *o) { (void)o; }
