// A jointed body's envelope: the faces of its surface that no other face covers (every view
// draws it; the cracks view translucent).
#pragma once
#include <vtkSmartPointer.h>

class vtkPolyData;

namespace dspdem::render {

/// The faces of `surface` that are not matched by a coincident face. Joints give every
/// element its own nodes, so a jointed body's surface holds each interior face twice, once per
/// element; what is left is the outer envelope and the faces of opened cracks. Points closer
/// than `tolerance` (a fraction of the bounds' diagonal) count as one, so a joint that has
/// opened less than that (an intact one) still pairs its two faces. Deterministic: the same
/// input gives the same faces in the same order, whatever the threads. The faces keep their
/// cell data (colours, field values) and share the merged points.
vtkSmartPointer<vtkPolyData> unmatched_faces(vtkPolyData* surface, double tolerance);

}  // namespace dspdem::render
