//! Imported modal data (frequencies and mode shapes from another FE program). Placeholder.
