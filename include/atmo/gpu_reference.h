/* gpu_reference.h — the order window of the Monte Carlo reference
 * (kernels/atmosphere/method_reference.h). Shared byte for byte with OpenCL C. */
#ifndef ATMO_GPU_REFERENCE_H
#define ATMO_GPU_REFERENCE_H

typedef struct atmo_gpu_reference {
    int min_order;  /* >= 1 */
    int max_order;  /* 0: all orders */
    int pad0, pad1;
} atmo_gpu_reference;

#endif
