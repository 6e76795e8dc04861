//! The wound program: a winding job planned layer by layer, moved to the
//! machine's axes, cut into timed NC blocks and written by a post-processor.
