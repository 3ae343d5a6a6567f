#include "wf725_fixture.hpp"
