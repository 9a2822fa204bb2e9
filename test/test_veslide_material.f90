!> Materials: complex compliance of the Prony laws, their limits, signs and equivalences, and
!> the refusal of bad constants
module test_veslide_material
    use veslide_kinds, only: dp
    use veslide_material, only: material_t, new_elastic, new_one_term, new_creep, new_relaxation
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use reference_oracles, only: paper_solid, einf, tau
    implicit none
    private
    public :: collect_material

contains

    subroutine collect_material(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("compliance-limits-and-sign", test_compliance), &
            new_unittest("relaxation-equals-creep", test_relaxation_creep), &
            new_unittest("elastic-is-frequency-independent", test_elastic), &
            new_unittest("loss-peak-of-the-standard-solid", test_loss_peak), &
            new_unittest("creep-sum-must-stay-below-1/E0", test_creep_sum, should_fail=.true., &
                         expect="sum of c_k must be below 1/E0"), &
            new_unittest("poisson-out-of-range", test_bad_poisson, should_fail=.true., expect="poisson") &
            ]
    end subroutine collect_material

    subroutine test_compliance(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        complex(dp) :: c
        integer :: k
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call check(error, real(m%compliance(0.0_dp), dp), 11.0_dp/einf, "C(0) = 1/E0", rel=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, real(m%compliance(1.0e12_dp/tau), dp), 1.0_dp/einf, "C(inf) = 1/Einf", rel=1.0e-10_dp)
        if (allocated(error)) return
        do k = -3, 3
            c = m%compliance(10.0_dp**k/tau)
            if (.not. aimag(c) < 0.0_dp) then
                call check(error, .false., "Im C(w) must be negative for w > 0"); return
            end if
        end do
        ! loss peak of E(w) = 1/C at w = Einf/(E0 tau) (notes, section 7)
        call check(error, aimag(1.0_dp/m%compliance(11.0_dp/tau)) > aimag(1.0_dp/m%compliance(11.0_dp/tau*1.05_dp)) &
                   .and. aimag(1.0_dp/m%compliance(11.0_dp/tau)) > aimag(1.0_dp/m%compliance(11.0_dp/tau/1.05_dp)), &
                   "loss modulus peaks at Einf/(E0 tau)")
    end subroutine test_compliance

    !> A one-term creep law is a one-term Maxwell relaxation law with rho = tau E0/Einf
    subroutine test_relaxation_creep(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: mc, mr
        real(dp) :: e0, w, worst
        integer :: k
        call paper_solid(11.0_dp, mc, error); if (allocated(error)) return
        e0 = einf/11.0_dp
        call new_relaxation(mr, e0, [einf - e0], [tau*e0/einf], 0.5_dp, error); if (allocated(error)) return
        worst = 0
        do k = -40, 40
            w = 10.0_dp**(k/10.0_dp)/tau
            worst = max(worst, abs(mc%compliance(w) - mr%compliance(w))*einf)
        end do
        call report("max |dC| Einf", worst)
        call check(error, worst <= 1.0e-14_dp, "creep and relaxation forms differ")
    end subroutine test_relaxation_creep

    !> An elastic solid has C = (1 - 0) / E at every frequency and no loss
    subroutine test_elastic(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_elastic(m, 2.0e7_dp, 0.3_dp, error); if (allocated(error)) return
        call check(error, m%is_elastic(), "is_elastic"); if (allocated(error)) return
        call check(error, all(m%compliance([0.0_dp, 1.0_dp, 1.0e9_dp]) == cmplx(1.0_dp/2.0e7_dp, 0.0_dp, dp)), &
                   "elastic compliance depends on frequency")
    end subroutine test_elastic

    !> sum c_k >= 1/E0 would make the glassy modulus infinite or negative: refused
    !> One-term (standard linear) solid: tan(delta) peaks at (Einf - E0)/(2 sqrt(E0 Einf)) where
    !> omega = 1/sqrt(tau_creep tau_relax) = sqrt(Einf/E0)/tau; an elastic solid has none
    subroutine test_loss_peak(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        real(dp) :: w, td, ratio
        ratio = 11.0_dp
        call new_one_term(m, einf, ratio, tau, 0.5_dp, error); if (allocated(error)) return
        call m%loss_peak(w, td)
        call report("omega rel. error", abs(w - sqrt(ratio)/tau)/(sqrt(ratio)/tau))
        call report("tan delta rel. error", abs(td - (ratio - 1.0_dp)/(2.0_dp*sqrt(ratio)))/((ratio - 1.0_dp)/ &
                                                                                             (2.0_dp*sqrt(ratio))))
        call check(error, w, sqrt(ratio)/tau, "peak frequency", rel=1.0e-6_dp); if (allocated(error)) return
        call check(error, td, (ratio - 1.0_dp)/(2.0_dp*sqrt(ratio)), "peak tan(delta)", rel=1.0e-10_dp)
        if (allocated(error)) return
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        call m%loss_peak(w, td)
        call check(error, w == 0.0_dp .and. td == 0.0_dp, "an elastic solid has no loss peak")
    end subroutine test_loss_peak

    subroutine test_creep_sum(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_creep(m, 1.0e6_dp, [6.0e-7_dp, 5.0e-7_dp], [1.0e-3_dp, 1.0e-2_dp], 0.5_dp, error)
    end subroutine test_creep_sum

    subroutine test_bad_poisson(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_one_term(m, einf, 11.0_dp, tau, 0.6_dp, error)
    end subroutine test_bad_poisson

end module test_veslide_material
