//! Bridge models as the engineer describes them: spans, supports, sections, girders, materials.
