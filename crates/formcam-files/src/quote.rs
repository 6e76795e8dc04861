//! Short, escaped excerpts of user text for error messages.
