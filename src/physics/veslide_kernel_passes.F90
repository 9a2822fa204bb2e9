!> The passes of the kernel's resolvent (veslide_kernel's `resolvent_t`), on either backend: the
!> CPU twins here, the CUDA twins in veslide_kernel_passes.cu.
!>  - `resolvent_multiplier`: mult = 1/((1 + gamma (K_d s)) N);
!>  - `resolvent_apply`: k = mult (k + gamma rk), and k(q = 0) = mean_x where this process holds it.
module veslide_kernel_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long
    use veslide_kinds, only: dp
    use veslide_arrays, only: carray_t, elements
    implicit none
    private
    public :: resolvent_multiplier, resolvent_apply

#ifdef VESLIDE_CUDA
    interface
        subroutine resolvent_multiplier_gpu(n, mult, kd, gamma, s, cells) bind(c, name='veslide_kernel_resolvent_multiplier')
            import :: c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: mult, kd
            real(c_double), value :: gamma, s, cells
        end subroutine resolvent_multiplier_gpu
        subroutine resolvent_apply_gpu(n, k, mult, rk, gamma, owns_mean, mean_x) bind(c, name='veslide_kernel_resolvent_apply')
            import :: c_long, c_ptr, c_double, c_int
            integer(c_long), value :: n
            type(c_ptr), value :: k, mult, rk
            real(c_double), value :: gamma, mean_x
            integer(c_int), value :: owns_mean
        end subroutine resolvent_apply_gpu
    end interface
#endif

contains

    !> mult = 1/((1 + gamma (kd s)) cells)
    subroutine resolvent_multiplier(mult, kd, gamma, s, cells)
        type(carray_t), intent(inout) :: mult
        type(carray_t), intent(in) :: kd
        real(dp), intent(in) :: gamma, s, cells
#ifdef VESLIDE_CUDA
        if (mult%device) then
            call resolvent_multiplier_gpu(elements(mult), mult%d, kd%d, gamma, s, cells); return
        end if
#endif
        call resolvent_multiplier_cpu(mult%h, kd%h, gamma, s, cells)
    end subroutine resolvent_multiplier

    !> k = mult (k + gamma rk); k(1, 1) = mean_x when `owns_mean`
    subroutine resolvent_apply(k, mult, rk, gamma, owns_mean, mean_x)
        type(carray_t), intent(inout) :: k
        type(carray_t), intent(in) :: mult, rk
        real(dp), intent(in) :: gamma, mean_x
        logical, intent(in) :: owns_mean
#ifdef VESLIDE_CUDA
        if (k%device) then
            call resolvent_apply_gpu(elements(k), k%d, mult%d, rk%d, gamma, &
                                     merge(1_c_int, 0_c_int, owns_mean), mean_x)
            return
        end if
#endif
        call resolvent_apply_cpu(k%h, mult%h, rk%h, gamma, owns_mean, mean_x)
    end subroutine resolvent_apply

    subroutine resolvent_multiplier_cpu(mult, kd, gamma, s, cells)
        complex(dp), intent(out) :: mult(:, :)
        complex(dp), intent(in) :: kd(:, :)
        real(dp), intent(in) :: gamma, s, cells
        mult = 1.0_dp/((1.0_dp + gamma*(kd*s))*cells)
    end subroutine resolvent_multiplier_cpu

    subroutine resolvent_apply_cpu(k, mult, rk, gamma, owns_mean, mean_x)
        complex(dp), intent(inout) :: k(:, :)
        complex(dp), intent(in) :: mult(:, :), rk(:, :)
        real(dp), intent(in) :: gamma, mean_x
        logical, intent(in) :: owns_mean
        k = mult*(k + gamma*rk)
        if (owns_mean) k(1, 1) = mean_x
    end subroutine resolvent_apply_cpu

end module veslide_kernel_passes
