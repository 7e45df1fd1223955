#pragma once
// The allocation tests replace the global operator new and delete (counting_new.cpp, compiled
// into each such test program) to count every C++ allocation.

/// The number of calls to any operator new so far in this program.
long counted_allocations();
