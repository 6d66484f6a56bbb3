// The object that carries the tests' precompiled header (support/precompiled.hpp); nothing else.
