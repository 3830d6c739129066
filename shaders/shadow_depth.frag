// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Shadow-map depth pass (shaders/Shadow.h, step 1): the terrain vertex stage
// with the sun's view-projection in FrameBlock writes the depth; no colour.

void main()
{
}
