# Motion cast (rotation by disk bounds with bisection): random rotating pairs of every kind against
# the conservative-advancement reference, closed forms, hard cases. MotionCastLong.* is the long
# run (10^5 casts), disabled unless asked for.
kairos_gtest(test_motion_cast SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_motion_cast.cpp LIBS kairos_core)
