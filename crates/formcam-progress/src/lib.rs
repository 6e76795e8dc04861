//! Progress reports and cancellation for the long pipelines: a pipeline
//! tells a hook how far it has come and asks it whether to stop.
